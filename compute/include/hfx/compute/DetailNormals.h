#pragma once
// An artist's tangent-space normal map kept on a field whose heights change: each apply() adds
// the relief the heights gained since the map was authored to the map's normals, in slope space
// (where heights add), so undamaged texels show the map exactly and craters bend it. The base
// heights' own Sobel normals are made once, at construction, for the same depth as the normals
// it is applied to.
//
// Owns its device buffers and kernel. Thread: the thread that owns the ClContext.

#include "hfx/compute/SobelNormals.h"

#include <vector>

namespace hfx {

class DetailNormals {
public:
    /// sobel: the size, edges and depth of the normals apply() will edit; baseHeights: the
    /// heights the map belongs to (width*height, row 0 at v = 0); detail: the map as width*height
    /// float4 (unit normal xyz, z >= 0; w unused), e.g. from packNormalMap. Sizes must match.
    DetailNormals(ClContext& cl, const SobelConfig& sobel, const std::vector<float>& baseHeights,
                  const std::vector<float>& detail);

    /// Enqueues: `normals` (float4, SobelNormals' output of the current heights, for the same
    /// depth) becomes the map plus the relief gained since the base heights, in place.
    void apply(const cl::Buffer& normals);

private:
    ClContext& cl_;
    int count_;
    SobelNormals baseNormals_;
    cl::Buffer detail_;
    cl::Kernel kernel_;
};

} // namespace hfx
