#pragma once
// Detail finer than a gas's grid, moved by its flow (FlowMath.h: texture advection with two
// regenerated layers). The gas planet's cloud tops: filaments where the jets shear, spiral arms
// around storms. Each step() advects the layers' noise coordinates with the gas's velocity (at
// the gas's resolution: coordinates are smooth); run() writes the heights at `scale` texels per
// gas cell: the gas's heights between cell centres, read where the layers' noises warp each
// point to and with their noise added, which carry the wavelengths the grid cannot.
//
// Owns its displacement planes, its output and its kernels. Thread: the thread that owns the
// ClContext.

#include "hfx/compute/GasField.h"

#include <cstdint>
#include <vector>

struct HfxFlowParams;

namespace hfx {

struct FlowDetailConfig {
    /// Output texels per gas cell along each axis: 1, 2, 4 or 8 (the output is a power of two
    /// wherever the gas is, for the height pyramid).
    int scale = 4;
    /// Heights get amount times the noise (about [-0.5, 0.5]), in [0, 1].
    float amount = 0.25f;
    /// The gas's heights are read at each point moved by up to half this many cells times the
    /// noise along each axis (FlowMath.h), in [0, 8]: band edges fray into filaments, flat
    /// bands stay flat. 0: no warp.
    float warp = 0.0f;
    /// The coarsest octave's lattice cells per gas cell along x; width * frequency must be whole
    /// (the noise wraps around the longitude). Each further octave doubles it.
    float frequency = 0.5f;
    /// The lattice's frequency along y over x's, [1, 8]: features that much longer along the
    /// bands than across them.
    float aspect = 2.0f;
    /// 1 to 8, at most: fewer where an octave would be finer than the output's texels can show
    /// (its lattice along y over scale / 2 per cell).
    int octaves = 4;
    /// The detail's share where the flow does not strain (a band's middle, a storm's eye), in
    /// [0, 1]; it reaches half way to all of it at a strain rate of strainScale per second.
    float calm = 0.3f;
    float strainScale = 0.3f;
    /// Simulated seconds a layer lives before it is regenerated: longer, the filaments stretch
    /// further; (0, 10^4].
    float period = 4.0f;
    /// Within capRows gas rows of the first and last rows the heights fade to 0.5 (a planet's
    /// poles); in [0, gas rows / 2].
    float capRows = 0.0f;
    std::uint64_t seed = 1; ///< the noises' generations start from it
    void validate(const GasConfig& gas) const; ///< throws hfx::Error naming the bad field
};

class FlowDetail {
public:
    /// The gas must outlive this; its edges must be wrap-u (the planet's).
    FlowDetail(ClContext& cl, const GasField& gas, const FlowDetailConfig& config);

    /// Advects both layers dt simulated seconds with the gas's present velocity (call beside
    /// the gas's step), regenerating a layer whose life ran out.
    void step(double dt);
    /// Enqueues the detailed heights of the gas's present heights into output().
    void run();
    const cl::Buffer& output() const { return output_; }
    int width() const { return gas_.width() * config_.scale; }
    int height() const { return gas_.height() * config_.scale; }
    const FlowDetailConfig& config() const { return config_; }
    double time() const { return time_; }

    /// Layer k's weight and noise generation now (the kernels' w_k, z_k).
    float weight(int layer) const;
    float generation(int layer) const;
    /// The planes (layer 0's displacement x, y, layer 1's x, y, the strain rate at the last step,
    /// and each layer's finest octave: FlowMath.h's HFX_FLOW_PLANES, each W x H at the cell
    /// centres), waits.
    std::vector<float> readPlanes();
    /// Replaces the first five (5 * W * H finite values); the finest octaves follow from them,
    /// for tests.
    void setPlanes(const std::vector<float>& planes);
    /// output() on the host (width() x height(), row 0 at v = 0), waits.
    std::vector<float> readHeights();
    /// The octaves the output's scale shows (config().octaves at most, at least 1).
    int octaves() const;
    /// What the detail kernel is given now besides the fields (FlowMath.h).
    HfxFlowParams params() const;

private:
    ClContext& cl_;
    const GasField& gas_;
    FlowDetailConfig config_;
    double time_ = 0.0;
    std::int64_t lives_[2] = {0, 0}; ///< each layer's regenerations so far
    cl::Buffer planes_[2], output_;
    int front_ = 0;
    cl::Kernel advect_, finest_, detail_;
    bool finestStale_ = true; ///< the displacements changed since the finest octaves were derived

    /// Each layer's finest octave from the front planes' displacements, where they changed: once
    /// for the steps between two runs (a frame's substeps, a spin-up), not once a step.
    void deriveFinest();
};

} // namespace hfx
