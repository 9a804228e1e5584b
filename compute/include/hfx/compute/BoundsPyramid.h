#pragma once
// Height-bounds mip pyramid of any height buffer: per texel the highest and the lowest height
// over its footprint (max: "minimum depth", the space a ray may skip; min: where a ray has
// certainly met the surface), rebuilt on the device each frame for tracers that skip empty space.
// Conservative for the *bilinear* surface: level 0 holds, per bilinear cell (between texel
// centres i..i+1, j..j+1), the max and min of its four corner samples; level k texel (I, J)
// bounds cells [I 2^k, (I+1) 2^k) x [J 2^k, (J+1) 2^k). All levels live in one buffer of
// (max, min) float pairs, level after level.
//
// Owns its buffer and kernels. Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"

#include <vector>

namespace hfx {

struct PyramidLevel {
    int width, height;
    size_t offset; ///< in texels ((max, min) pairs) from the start of the buffer
};

class BoundsPyramid {
public:
    /// Along an axis that wraps (the source's edges), the last cell joins the last sample to the
    /// first, as the wrapped texture interpolates; along one that clamps it holds the last sample.
    BoundsPyramid(ClContext& cl, int width, int height, EdgeMode edges);

    /// Enqueues the whole pyramid of `height` (width x height floats); does not wait.
    void build(const cl::Buffer& height);

    const cl::Buffer& buffer() const { return buffer_; }
    const std::vector<PyramidLevel>& levels() const { return levels_; }
    /// Texels over all levels; the buffer holds two floats (max, min) per texel.
    size_t totalTexels() const;

private:
    ClContext& cl_;
    int width_, height_;
    std::vector<PyramidLevel> levels_;
    cl::Buffer buffer_;
    cl::Kernel cells_, reduce_;
};

} // namespace hfx
