#pragma once
// A Navier-Stokes gas (Stam's stable fluids; Harris, GPU Gems ch. 38) on a staggered grid:
// semi-Lagrangian advection (MacCormack optional), implicit viscosity, vorticity confinement,
// pressure projection by Jacobi iterations, advected dye, splats of force and dye, and zonal
// jets for banded planets. x is periodic (longitude wraps); y is periodic or bounded by walls.
// The height field is the dye, so the gas's bands and vortices read as relief.
//
// Grid units: lengths in cells, velocities in cells per second. See shared/GasMath.h.
// Thread: the thread that owns the ClContext.

#include "hfx/compute/HeightSource.h"

#include <cstdint>
#include <vector>

namespace hfx {

struct GasConfig {
    int width = 256;
    int height = 128;
    /// x always wraps (longitude). WrapU: walls at the top and bottom (poles); Wrap: a torus.
    EdgeMode edges = EdgeMode::WrapU;
    float viscosity = 0.0f;       ///< cells^2 per second
    int viscosityIterations = 20;
    int pressureIterations = 40;
    float vorticity = 0.0f;       ///< confinement strength epsilon
    bool maccormack = false;      ///< second-order MacCormack advection (costlier: docs/history/tuning.md)
    bool conserveDye = true;      ///< rescale the dye after advection to keep its total
    float jetSpeed = 0.0f;        ///< zonal jets: u relaxes to jetSpeed sin(2 pi jetBands y / H)
    float jetBands = 3.0f;
    float jetRate = 0.05f;        ///< relaxation rate of the jets, per second
    /// The jets fade towards the walls as sin(pi y / H)^jetPolar (a planet's poles); 0: no fade.
    float jetPolar = 0.0f;
    /// After the forces, each velocity component is clamped to +-maxSpeed cells per second, so
    /// steps of any length stay bounded (the planet's large time scales); 0: no clamp.
    float maxSpeed = 0.0f;
    float initialBands = 0.0f;    ///< dye starts as 0.5 + 0.45 sin(2 pi bands y / H) plus noise
    /// 0: every initial band alike. Up to 1: each zone and belt (each half period of the bands)
    /// gets its own depth, down to 1 - 0.6 variety of the full swing, and thinner bands inside it
    /// of up to 0.12 variety, drawn from the seed: belts and zones of different shades, as a
    /// gas giant's are.
    float bandVariety = 0.0f;
    /// Per second, in [0, 1]: the dye relaxes towards its initial bands (each row's starting
    /// value, without the noise) at this rate, as a giant's zones and belts are kept by up- and
    /// downwelling while storms and shear mix them; 0: it only mixes (and, in time, greys out).
    float dyeRate = 0.0f;
    std::uint64_t seed = 1;
    void validate() const;
};

/// Force and dye added around a point during the next step. Texcoords; radius in widths.
struct GasSplat {
    float u = 0.5f, v = 0.5f;
    float radius = 0.03f;
    float forceX = 0.0f, forceY = 0.0f; ///< cells per second^2, applied over the step
    float dye = 0.0f;                   ///< added at the centre, clamped to [0,1]
};

class GasField final : public HeightSource {
public:
    GasField(ClContext& cl, const GasConfig& config);

    void step(double dt) override;
    void addSplat(const GasSplat& splat); ///< throws hfx::Error for a splat off the map
    /// The splats queued for the next step, in order.
    const std::vector<GasSplat>& pendingSplats() const { return splats_; }
    /// Runs only the pressure projection (tests, and after setting a velocity by hand).
    void project();

    /// Host access to the state (row-major W x H; see GasMath.h for where each lives).
    void setState(const std::vector<float>& u, const std::vector<float>& v, const std::vector<float>& dye);
    void readState(std::vector<float>& u, std::vector<float>& v, std::vector<float>& dye);
    /// The heights buffer() holds (row 0 at v = 0), waiting for the queue.
    std::vector<float> readHeights();
    /// The divergence the projection's Laplacian matches: outflow through each cell's faces.
    std::vector<float> readDivergence();

    const cl::Buffer& buffer() const override { return height_; }
    /// The velocity's faces on the device (cells per second; GasMath.h says where each lives),
    /// for passes that move with the gas (FlowDetail).
    const cl::Buffer& velocityX() const { return u_; }
    const cl::Buffer& velocityY() const { return v_; }
    int width() const override { return config_.width; }
    int height() const override { return config_.height; }
    EdgeMode edges() const override { return config_.edges; }
    const GasConfig& config() const { return config_; }

private:
    /// Sets the kernel's arguments in order and enqueues it over `range` (default: every cell).
    void run(cl::Kernel& kernel, std::initializer_list<std::pair<size_t, const void*>> args,
             cl::NDRange range = cl::NullRange);
    void advectField(cl::Buffer& field, float ox, float oy, float dt, bool wallRow);
    void writeHeight();

    ClContext& cl_;
    GasConfig config_;
    std::vector<GasSplat> splats_;
    cl::Buffer u_, v_, dye_, work_[4], p_, p2_, div_, curl_, height_, sumsBefore_, sumsAfter_, factor_, bandRows_;
    cl::Kernel advect_, maccormack_, splat_, jets_, clampSpeed_, curlKernel_, confine_, diffuse_, divergence_,
        pressure_, project_, dyeHeight_, rowSums_, massFactor_, scale_, relaxDye_;
};

} // namespace hfx
