#include "hfx/effects/ImageSurface.h"

#include "hfx/core/Error.h"
#include "hfx/core/SurfaceMaps.h"

namespace hfx {

void ImageSurfaceConfig::validate() const {
    if (maps.heights.empty()) throw Error("ImageSurfaceConfig.maps has no heights: a height map is required");
    maps.validate();
    material.validate();
}

ImageSurface::ImageSurface(ClContext& cl, const ImageSurfaceConfig& config)
    // Everything is checked before anything is made on a device, so bad maps leave no
    // half-made textures behind.
    : Effect((config.validate(), config.material)),
      heights_(cl, config.maps.width, config.maps.height, config.edges, config.maps.heights),
      surface_(cl, SurfacePipelineConfig::of(heights_, config.material.depthScale, config.surface)) {
    const SurfaceMaps& maps = config.maps;
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
