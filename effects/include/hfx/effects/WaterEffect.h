#pragma once
// Procedural water: a FieldEffect over the directional-waves source. Draw it with
// SurfaceRenderer on a plane whose texcoords repeat the (tileable) patch.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/WaveField.h"
#include "hfx/effects/FieldEffect.h"

namespace hfx {

struct WaterConfig {
    WaveConfig waves;
    SurfaceMaterial material{.depthScale = 0.04f, .shadowSharpness = 1.0f,
                             .specularStrength = 0.8f, .specularPower = 96.0f};
    FieldOptions surface; ///< mip maps, height pyramid, storage format, path to GL
    void validate() const;
};

class WaterEffect final : public FieldEffect {
public:
    WaterEffect(ClContext& cl, const WaterConfig& config = {});

    /// Jumps to an absolute time (seconds) and refreshes the textures.
    void setTime(double seconds);
    double time() const { return waves_.time(); }
    const WaveField& waves() const { return waves_; }

private:
    WaveField& waves_;
};

} // namespace hfx
