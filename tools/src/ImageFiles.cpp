#include "hfx/tools/ImageFiles.h"

#include "hfx/core/Error.h"

namespace hfx {

#if !defined(HFX_WITH_OPENIMAGEIO)
const ImageCodec* openImageIoCodec() { return nullptr; }
#endif

const ImageCodec& imageCodec() {
#if defined(HFX_WITH_OPENIMAGEIO)
    return *openImageIoCodec();
#else
    return lightImageCodec();
#endif
}

Image readImage(const std::string& path, const ImageReadLimits& limits) { return imageCodec().read(path, limits); }

ImageSize readImageSize(const std::string& path, const ImageReadLimits& limits) {
    return imageCodec().readSize(path, limits);
}

void writeImage(const std::string& path, const Image& image) { imageCodec().write(path, image); }

SurfaceMaps readSurfaceMaps(const std::string& heightMap, const std::string& normalMap, const std::string& colorMap,
                            const ImageReadLimits& limits) {
    const Image height = readImage(heightMap, limits);
    Image normal, color;
    if (!normalMap.empty()) normal = readImage(normalMap, limits);
    if (!colorMap.empty()) color = readImage(colorMap, limits);
    return surfaceMapsFromImages(height, heightMap, normalMap.empty() ? nullptr : &normal, normalMap,
                                 colorMap.empty() ? nullptr : &color, colorMap);
}

} // namespace hfx
