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

/// Tangent-space normals from an OpenGL-convention normal map (+Y = up in the image = +v), RGB
/// in [0,1] decoding to 2c - 1, renormalised; packed as float4 (normal.xyz, height) with the
/// given heights. Sizes must match.
std::vector<float> packNormalMap(const Image& normalMap, const std::string& path,
                                 const std::vector<float>& heights);

} // namespace hfx
