#pragma once
// A surface from files: a height map (any format OpenImageIO reads, 8-bit or better), an
// optional tangent-space normal map and an optional colour map. Without a normal map the
// normals come from the device's Sobel kernel, like a generated field's. Loaded once; the
// surface is static, so update() only counts time.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/ClContext.h"
#include "hfx/core/Image.h"
#include "hfx/effects/Effect.h"

#include <string>

namespace hfx {

struct ImageSurfaceConfig {
    std::string heightMap;  ///< required
    std::string normalMap;  ///< optional: derived from the heights when empty
    std::string colorMap;   ///< optional: light grey when empty
    SurfaceMaterial material{.depthScale = 0.08f};
    EdgeMode edges = EdgeMode::Wrap; ///< tileable maps wrap; others clamp
    bool mipmaps = true;
    ImageReadLimits limits;
    void validate() const;
};

class ImageSurface final : public Effect {
public:
    /// Throws hfx::Error naming the file for a missing, corrupt, mismatched or out-of-range map.
    ImageSurface(ClContext& cl, const ImageSurfaceConfig& config);

    void update(double dt) override;
    const SurfaceTextures& textures() const override { return textures_; }
    const SurfaceMaterial& material() const override { return config_.material; }
    std::string transferDescription() const override {
        return std::string(surfaceFormatName(textures_.config().format)) + " texels, uploaded once";
    }
    StageTimes lastTimes() const override { return {}; }

private:
    ImageSurfaceConfig config_;
    SurfaceTextures textures_;
};

} // namespace hfx
