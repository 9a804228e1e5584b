#pragma once
// Ocean-like height field: a sum of directional waves on a tileable square patch, animated with
// the deep-water dispersion relation omega^2 = g k. Each wave has whole cycles across the patch
// (wave vectors on the patch's lattice), so the field tiles exactly at every time.
// Writes h in [0,1] into a float buffer of size x size, row y at v = (y + 0.5) / size.
//
// Owns its buffers and kernel. Thread: the thread that owns the ClContext.

#include "hfx/compute/HeightSource.h"

#include <cstdint>
#include <vector>

namespace hfx {

struct WaveConfig {
    int size = 512;               ///< texels per edge
    int waveCount = 24;
    float patchMeters = 40.0f;    ///< physical edge of the patch, sets speeds through omega^2 = g k
    float windDirection = 0.6f;   ///< radians from +u
    float spread = 0.7f;          ///< half-width of the directions around the wind, radians
    int minCycles = 2;            ///< longest wave: patch / maxCycles .. patch / minCycles
    int maxCycles = 20;
    float steepness = 0.15f;      ///< Stokes-like crest sharpening in [0, 0.25], 0 = sine
    std::uint32_t seed = 1;
    void validate() const;        ///< throws hfx::Error naming the bad field and its value
};

/// One wave: (m, n) cycles across the patch, amplitude, angular frequency, phase at t = 0.
struct Wave {
    float m, n, amplitude, omega, phase;
};

class WaveField final : public HeightSource {
public:
    WaveField(ClContext& cl, const WaveConfig& config);

    /// Advances time by dt seconds (dt > 0, finite) and recomputes the field.
    void step(double dt) override;
    /// Sets the absolute time and recomputes the field.
    void setTime(double seconds);
    double time() const { return time_; }

    const cl::Buffer& buffer() const override { return height_; }
    int width() const override { return config_.size; }
    int height() const override { return config_.size; }
    EdgeMode edges() const override { return EdgeMode::Wrap; }
    int size() const { return config_.size; }
    const WaveConfig& config() const { return config_; }
    const std::vector<Wave>& waves() const { return waves_; }

    /// The deterministic wave set a config produces (same on every platform).
    static std::vector<Wave> makeWaves(const WaveConfig& config);
    /// Phase of each wave at time t, reduced to [0, 2 pi) in double precision.
    static float phaseAt(const Wave& wave, double seconds);
    static float inverseTotalAmplitude(const std::vector<Wave>& waves);

private:
    void compute();

    ClContext& cl_;
    WaveConfig config_;
    std::vector<Wave> waves_;
    std::vector<cl_float4> packed_; ///< per-frame staging of (m, n, amplitude, phase)
    cl::Buffer waveBuffer_, columns_, rows_, height_;
    cl::Kernel tables_, kernel_;
    double time_ = 0.0;
};

} // namespace hfx
