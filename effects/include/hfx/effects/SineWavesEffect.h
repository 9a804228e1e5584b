#pragma once
// Directional sine waves (WaveField: a sum of tileable waves with deep-water dispersion) as a
// lit surface: the cheap animated relief, Blinn-Phong shaded unless the material says otherwise
// (the water scene's `--waves sine` shades it as water). Draw it with SurfaceRenderer on a plane
// whose texcoords repeat the (tileable) patch.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/WaveField.h"
#include "hfx/effects/Effect.h"

namespace hfx {

struct SineWavesConfig {
    WaveConfig waves;
    SurfaceMaterial material{.depthScale = 0.04f, .shadowSharpness = 1.0f,
                             .specularStrength = 0.8f, .specularPower = 96.0f};
    SurfaceOptions surface; ///< mip maps, storage format, path to GL
    void validate() const;  ///< throws hfx::Error naming the bad field and its value
};

class SineWavesEffect final : public Effect {
public:
    explicit SineWavesEffect(ClContext& cl, const SineWavesConfig& config = {});

    /// Jumps to an absolute time (seconds) and refreshes the textures.
    void setTime(double seconds);
    double time() const { return waves_.time(); }
    const WaveField& waves() const { return waves_; }

private:
    const SurfacePipeline& surface() const override { return surface_; }
    void advance(double dt) override { waves_.step(dt); }
    void enqueueSurface() override;

    WaveField waves_;
    SurfacePipeline surface_;
};

} // namespace hfx
