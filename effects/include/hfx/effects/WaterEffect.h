#pragma once
// Procedural water: waves -> Sobel normals -> GL upload, every update. Draw it with
// SurfaceRenderer on a plane whose texcoords repeat the (tileable) patch.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/SobelNormals.h"
#include "hfx/compute/WaveField.h"
#include "hfx/effects/Effect.h"

namespace hfx {

struct WaterConfig {
    WaveConfig waves;
    SurfaceMaterial material{.depthScale = 0.04f, .shadowSharpness = 1.0f,
                             .specularStrength = 0.8f, .specularPower = 96.0f};
    bool mipmaps = true;
    void validate() const;
};

class WaterEffect final : public Effect {
public:
    WaterEffect(ClContext& cl, const WaterConfig& config = {});

    void update(double dt) override;
    /// Jumps to an absolute time (seconds) and refreshes the textures.
    void setTime(double seconds);
    double time() const { return waves_.time(); }

    const SurfaceTextures& textures() const override { return textures_; }
    const SurfaceMaterial& material() const override { return config_.material; }
    StageTimes lastTimes() const override { return times_; }
    const WaveField& waves() const { return waves_; }
    const SobelNormals& normals() const { return normals_; }

private:
    void refresh(double computeStartMs);

    ClContext& cl_;
    WaterConfig config_;
    WaveField waves_;
    SobelNormals normals_;
    SurfaceTextures textures_;
    StageTimes times_;
};

} // namespace hfx
