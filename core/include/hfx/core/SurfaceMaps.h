#pragma once
// Turning image files into the surface layout: heights and tangent-space normals as the compute
// kernels lay them out (row 0 at v = 0, the bottom of the image), refused with the file's name
// when they do not fit.
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

/// The maps of one surface read from files and checked against each other.
struct SurfaceMaps {
    int width = 0, height = 0;
    std::vector<float> heights; ///< width*height, row 0 at v = 0 (heightsFromImage)
    std::vector<float> normals; ///< packNormalMap's float4s, or empty without a normal map
    Image color;                ///< as read (top row first), or empty without a colour map
};

/// Reads a height map and, when their paths are not empty, a normal and a colour map of the same
/// size. Throws hfx::Error naming the file that is missing, corrupt, out of range or of another
/// size; nothing is returned half-read.
SurfaceMaps readSurfaceMaps(const std::string& heightMap, const std::string& normalMap, const std::string& colorMap,
                            const ImageReadLimits& limits = {});

/// Tangent-space normals from an OpenGL-convention normal map (+Y = up in the image = +v), RGB
/// in [0,1] decoding to 2c - 1, renormalised; packed as float4 (normal.xyz, height) with the
/// given heights. Sizes must match.
std::vector<float> packNormalMap(const Image& normalMap, const std::string& path,
                                 const std::vector<float>& heights);

} // namespace hfx
