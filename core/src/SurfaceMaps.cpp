#include "hfx/core/SurfaceMaps.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>

namespace hfx {

std::vector<float> heightsFromImage(const Image& image, const std::string& path) {
    if (image.empty() || image.width < 1 || image.height < 1)
        throw Error(str("height map '", path, "' is empty"));
    std::vector<float> heights(size_t(image.width) * image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float h = image.at(x, image.height - 1 - y, 0);
            if (!(h >= 0.0f && h <= 1.0f))
                throw Error(str("height map '", path, "' has the value ", h, " at pixel (", x, ", ",
                                image.height - 1 - y, "); heights must lie in [0,1]"));
            heights[size_t(y) * image.width + x] = h;
        }
    return heights;
}

std::vector<float> packNormalMap(const Image& normalMap, const std::string& path,
                                 const std::vector<float>& heights) {
    if (normalMap.channels < 3)
        throw Error(str("normal map '", path, "' has ", normalMap.channels,
                        " channel(s); it needs RGB"));
    if (size_t(normalMap.width) * normalMap.height != heights.size())
        throw Error(str("normal map '", path, "' is ", normalMap.width, "x", normalMap.height,
                        ", which does not match the height map (", heights.size(), " texels)"));
    std::vector<float> packed(heights.size() * 4);
    for (int y = 0; y < normalMap.height; ++y)
        for (int x = 0; x < normalMap.width; ++x) {
            const int row = normalMap.height - 1 - y;
            float n[3];
            for (int c = 0; c < 3; ++c) n[c] = 2.0f * normalMap.at(x, row, c) - 1.0f;
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(length > 1e-3f) || n[2] < 0.0f)
                throw Error(str("normal map '", path, "' has no usable normal at pixel (", x, ", ",
                                row, "): a tangent-space normal map encodes z >= 0"));
            const size_t i = size_t(y) * normalMap.width + x;
            for (int c = 0; c < 3; ++c) packed[i * 4 + c] = n[c] / length;
            packed[i * 4 + 3] = heights[i];
        }
    return packed;
}

SurfaceMaps surfaceMapsFromImages(const Image& height, const std::string& heightName, const Image* normal,
                                  const std::string& normalName, const Image* color, const std::string& colorName) {
    SurfaceMaps maps;
    maps.width = height.width;
    maps.height = height.height;
    maps.heights = heightsFromImage(height, heightName);
    if (normal) maps.normals = packNormalMap(*normal, normalName, maps.heights);
    if (color) {
        if (color->width != height.width || color->height != height.height)
            throw Error(str("colour map '", colorName, "' is ", color->width, "x", color->height, " but the height map '",
                            heightName, "' is ", height.width, "x", height.height));
        maps.color = *color;
    }
    return maps;
}

void SurfaceMaps::validate() const {
    const size_t texels = size_t(std::max(width, 0)) * size_t(std::max(height, 0));
    if (width < 1 || height < 1 || heights.size() != texels)
        throw Error(str("SurfaceMaps: ", heights.size(), " heights for a ", width, "x", height, " surface"));
    for (size_t i = 0; i < heights.size(); ++i)
        if (!(heights[i] >= 0.0f && heights[i] <= 1.0f))
            throw Error(str("SurfaceMaps.heights[", i, "] is ", heights[i], "; heights must lie in [0,1]"));
    if (!normals.empty() && normals.size() != 4 * texels)
        throw Error(str("SurfaceMaps.normals holds ", normals.size(), " floats, a ", width, "x", height,
                        " surface needs ", 4 * texels, " (float4s)"));
    if (!color.empty() && (color.width != width || color.height != height ||
                           color.pixels.size() != texels * size_t(std::max(color.channels, 0))))
        throw Error(str("SurfaceMaps.color is ", color.width, "x", color.height, "x", color.channels, ", the surface ",
                        width, "x", height));
}

} // namespace hfx
