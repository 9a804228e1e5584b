#pragma once
// Turning images into the surface layout: heights and tangent-space normals as the compute
// kernels lay them out (row 0 at v = 0, the bottom of the image), refused with the image's name
// (its file, where it came from one) when they do not fit. The module reads no file: the tools'
// readSurfaceMaps (hfx/tools/ImageFiles.h) or an engine's own loaders make the Images.
//
// Returns owned vectors. Thread: any; no GL calls.

#include "hfx/core/Image.h"

#include <string>
#include <vector>

namespace hfx {

/// Heights from the first channel of `image` (read from `path`, named in errors), rows flipped
/// so row 0 is the image's bottom. 8/16-bit images map to [0,1] as stored; float images must
/// already lie in [0,1] (values outside are refused, not clamped).
std::vector<float> heightsFromImage(const Image& image, const std::string& path);

/// The maps of one surface, checked against each other.
struct SurfaceMaps {
    int width = 0, height = 0;
    std::vector<float> heights; ///< width*height in [0,1], row 0 at v = 0 (heightsFromImage)
    std::vector<float> normals; ///< packNormalMap's float4s, or empty without a normal map
    Image color;                ///< top row first, or empty without a colour map
    /// Throws hfx::Error naming the field that does not fit the size (or a height outside [0,1]).
    void validate() const;
};

/// The maps from a height image and, where given (not null), a normal and a colour image of the
/// same size; each name (a file's path) is what errors call it.
SurfaceMaps surfaceMapsFromImages(const Image& height, const std::string& heightName, const Image* normal = nullptr,
                                  const std::string& normalName = {}, const Image* color = nullptr,
                                  const std::string& colorName = {});

/// Tangent-space normals from an OpenGL-convention normal map (+Y = up in the image = +v), RGB
/// in [0,1] decoding to 2c - 1, renormalised; packed as float4 (normal.xyz, height) with the
/// given heights. Sizes must match.
std::vector<float> packNormalMap(const Image& normalMap, const std::string& path,
                                 const std::vector<float>& heights);

} // namespace hfx
