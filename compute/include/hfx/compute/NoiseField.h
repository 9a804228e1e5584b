#pragma once
// Animated gradient-noise height fields: Perlin's Improved Noise, simplex noise, or psrdnoise
// (periodic, with rotating gradients); as fBm, ridged or turbulence octave sums, optionally
// domain-warped, optionally tileable. Time moves Perlin and simplex through their third
// dimension and turns psrdnoise's gradients (the flow look).
//
// Owns its buffers and kernels. Thread: the thread that owns the ClContext.

#include "hfx/compute/HeightSource.h"
#include "hfx/compute/shared/NoiseMath.h"

#include <string>

namespace hfx {

enum class NoiseKind { Perlin = HFX_NOISE_PERLIN, Simplex = HFX_NOISE_SIMPLEX, Psrd = HFX_NOISE_PSRD };
enum class Fractal { Fbm = HFX_FRACTAL_FBM, Ridged = HFX_FRACTAL_RIDGED, Turbulence = HFX_FRACTAL_TURBULENCE };

/// "perlin", "simplex", "psrd" / "fbm", "ridged", "turbulence"; throws naming the value.
NoiseKind parseNoiseKind(const std::string& name);
Fractal parseFractal(const std::string& name);

struct NoiseConfig {
    int width = 512;
    int height = 512;
    NoiseKind kind = NoiseKind::Perlin;
    Fractal fractal = Fractal::Fbm;
    float frequency = 8.0f;  ///< base cells across the width (whole number when it wraps)
    int octaves = 5;
    float lacunarity = 2.0f; ///< frequency ratio of successive octaves (whole when it wraps)
    float gain = 0.5f;       ///< amplitude ratio of successive octaves
    float warp = 0.0f;       ///< domain-warp distance in base cells, 0 = none
    float speed = 0.3f;      ///< time-coordinate units (or radians for psrd) per second
    /// Wrap: tileable (Perlin and psrd); WrapU: tileable in u only (Perlin); Clamp: not tileable
    /// (any kind; simplex has no periodic variant).
    EdgeMode edges = EdgeMode::Wrap;
    float seed = 0.0f;       ///< start of the time coordinate: different seeds, different fields
    void validate() const;   ///< throws hfx::Error naming the bad field and its value
    /// Cells across the height: the width's frequency scaled by the aspect (psrdnoise's y period
    /// must be even, so it is rounded to one).
    float frequencyY() const;
};

class NoiseField final : public HeightSource {
public:
    NoiseField(ClContext& cl, const NoiseConfig& config);

    void step(double dt) override;
    void setTime(double seconds);
    double time() const { return time_; }

    const cl::Buffer& buffer() const override { return height_; }
    int width() const override { return config_.width; }
    int height() const override { return config_.height; }
    EdgeMode edges() const override { return config_.edges; }
    const NoiseConfig& config() const { return config_; }
    /// The time coordinate the kernel sees at `seconds`.
    float timeCoordinate(double seconds) const;

private:
    void compute();

    ClContext& cl_;
    NoiseConfig config_;
    cl::Buffer height_;
    cl::Kernel kernel_;
    double time_ = 0.0;
};

} // namespace hfx
