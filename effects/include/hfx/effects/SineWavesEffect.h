#pragma once
// Directional sine waves (WaveField: a sum of tileable waves with deep-water dispersion) as a
// lit surface: the cheap animated relief, Blinn-Phong shaded unless the material says otherwise
// (the water scene's `--waves sine` shades it as water). Draw it with SurfaceRenderer on a plane
// whose texcoords repeat the (tileable) patch.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/WaveField.h"
#include "hfx/effects/FieldEffect.h"

namespace hfx {

struct SineWavesConfig {
    WaveConfig waves;
    SurfaceMaterial material{.depthScale = 0.04f, .shadowSharpness = 1.0f,
                             .specularStrength = 0.8f, .specularPower = 96.0f};
    FieldOptions surface; ///< mip maps, height pyramid, storage format, path to GL
    void validate() const;
};

class SineWavesEffect final : public FieldEffect {
public:
    SineWavesEffect(ClContext& cl, const SineWavesConfig& config = {});

    /// Jumps to an absolute time (seconds) and refreshes the textures.
    void setTime(double seconds);
    double time() const { return waves_.time(); }
    const WaveField& waves() const { return waves_; }

private:
    WaveField& waves_;
};

} // namespace hfx
