#include "hfx/effects/ImageSurface.h"

#include "hfx/compute/SobelNormals.h"
#include "hfx/core/Error.h"
#include "hfx/core/SurfaceMaps.h"
#include "hfx/effects/FieldUpload.h"

#include <cmath>

namespace hfx {
namespace {

struct LoadedMaps {
    Image height;
    std::vector<float> heights;
};

LoadedMaps loadHeights(const ImageSurfaceConfig& config) {
    LoadedMaps maps;
    maps.height = readImage(config.heightMap, config.limits);
    maps.heights = heightsFromImage(maps.height, config.heightMap);
    return maps;
}

SurfaceTexturesConfig texturesConfig(const ImageSurfaceConfig& config, const Image& height) {
    return {.width = height.width,
            .height = height.height,
            .mipmaps = config.mipmaps,
            .edges = config.edges};
}

} // namespace

void ImageSurfaceConfig::validate() const {
    if (heightMap.empty()) throw Error("ImageSurfaceConfig.heightMap is empty: a height map is required");
    material.validate();
}

ImageSurface::ImageSurface(ClContext& cl, const ImageSurfaceConfig& config)
    : config_((config.validate(), config)),
      textures_([&] {
          // Read everything before touching GL, so a bad file leaves no half-made textures.
          const LoadedMaps maps = loadHeights(config);
          const Image normal = config.normalMap.empty() ? Image{} : readImage(config.normalMap, config.limits);
          const Image color = config.colorMap.empty() ? Image{} : readImage(config.colorMap, config.limits);
          if (!color.empty() && (color.width != maps.height.width || color.height != maps.height.height))
              throw Error(str("colour map '", config.colorMap, "' is ", color.width, "x", color.height,
                              " but the height map '", config.heightMap, "' is ", maps.height.width,
                              "x", maps.height.height));
          const std::vector<float> packed =
              normal.empty() ? std::vector<float>{} : packNormalMap(normal, config.normalMap, maps.heights);

          SurfaceTextures textures(texturesConfig(config, maps.height));
          if (!color.empty()) textures.setAlbedo(color);
          if (!packed.empty()) {
              textures.upload(packed.data());
          } else {
              const int w = maps.height.width, h = maps.height.height;
              cl::Buffer heights = clGuard("uploading the height map", [&] {
                  return cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                    maps.heights.size() * sizeof(float),
                                    const_cast<float*>(maps.heights.data()));
              });
              SobelNormals sobel(cl, {.width = w,
                                      .height = h,
                                      .depthScale = config.material.depthScale,
                                      .edges = config.edges});
              sobel.run(heights);
              uploadField(cl, sobel.output(), textures);
          }
          return textures;
      }()) {}

void ImageSurface::update(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("ImageSurface::update: dt must be positive and finite, got ", dt));
}

} // namespace hfx
