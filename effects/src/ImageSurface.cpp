#include "hfx/effects/ImageSurface.h"

#include "hfx/core/Error.h"
#include "hfx/core/SurfaceMaps.h"

namespace hfx {

void ImageSurfaceConfig::validate() const {
    if (heightMap.empty()) throw Error("ImageSurfaceConfig.heightMap is empty: a height map is required");
    material.validate();
}

SurfaceMaps ImageSurface::load(const ImageSurfaceConfig& config) {
    // Everything is read and checked before anything is made on a device, so a bad file
    // leaves no half-made textures behind.
    config.validate();
    return readSurfaceMaps(config.heightMap, config.normalMap, config.colorMap, config.limits);
}

ImageSurface::ImageSurface(ClContext& cl, const ImageSurfaceConfig& config)
    : ImageSurface(cl, config, load(config)) {}

ImageSurface::ImageSurface(ClContext& cl, const ImageSurfaceConfig& config, SurfaceMaps maps)
    : Effect(config.material), heights_(cl, maps.width, maps.height, config.edges, maps.heights),
      surface_(cl, SurfacePipelineConfig::of(heights_, config.material.depthScale, config.surface)) {
    if (!maps.color.empty()) surface_.setAlbedo(maps.color);
    if (!maps.normals.empty()) {
        detail_ = std::make_unique<DetailNormals>(cl, surface_.config().sobel(), maps.heights, maps.normals);
    }
    refresh();
}

void ImageSurface::enqueueSurface() {
    if (derived_) return;
    surface_.derive(heights_.buffer());
    if (detail_) detail_->apply(surface_.normals());
    surface_.submit();
    derived_ = true;
}

} // namespace hfx
