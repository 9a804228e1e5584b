#pragma once
// Noise as a surface an artist can look at: any NoiseField configuration (kind, fractal,
// octaves, warp, tiling) as a lit, animated relief coloured through a ramp, that setNoise()
// replaces live (the demo's `noise` scene and its panel); export it with the demo's
// --export-maps. Draw it on a plane whose texcoords repeat the patch to see the tiling.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/ColorRamp.h"
#include "hfx/compute/NoiseField.h"
#include "hfx/effects/Effect.h"

#include <memory>
#include <vector>

namespace hfx {

/// Earth to stone to pale rock, low to high.
std::vector<ColorStop> noisePalette();

struct NoiseSurfaceConfig {
    NoiseConfig noise{.width = 256, .height = 256, .frequency = 6.0f};
    std::vector<ColorStop> palette = noisePalette();
    SurfaceMaterial material{.depthScale = 0.06f, .maxSamples = 48, .shadowSharpness = 2.0f,
                             .specularStrength = 0.15f, .specularPower = 24.0f};
    SurfaceOptions surface; ///< mip maps, storage format, path to GL
    void validate() const;  ///< throws hfx::Error naming the bad field and its value
};

class NoiseSurfaceEffect final : public Effect {
public:
    explicit NoiseSurfaceEffect(ClContext& cl, const NoiseSurfaceConfig& config = {});

    /// Another noise (any option, any tiling; the same size or another), from the next frame;
    /// it keeps the time. Throws hfx::Error naming the bad field and changes nothing. Call it
    /// between frames (it waits for the device).
    void setNoise(const NoiseConfig& noise);
    const NoiseField& noise() const { return *noise_; }
    void setTime(double seconds);

private:
    const SurfacePipeline& surface() const override { return *surface_; }
    void advance(double dt) override { noise_->step(dt); }
    void enqueueSurface() override;

    ClContext& cl_;
    NoiseSurfaceConfig config_;
    std::unique_ptr<NoiseField> noise_;
    std::unique_ptr<ColorRamp> colors_;
    std::unique_ptr<SurfacePipeline> surface_;
};

} // namespace hfx
