#pragma once
// Maximum-height mip pyramid ("minimum depth") of any height buffer, rebuilt on the device each
// frame, for tracers that skip empty space. Conservative for the *bilinear* surface: level 0
// holds, per bilinear cell (between texel centres i..i+1, j..j+1), the max of its four corner
// samples; level k texel (I, J) bounds cells [I 2^k, (I+1) 2^k) x [J 2^k, (J+1) 2^k).
// All levels live in one buffer, level after level.
//
// Owns its buffer and kernels. Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"

#include <vector>

namespace hfx {

struct PyramidLevel {
    int width, height;
    size_t offset; ///< in floats from the start of the buffer
};

class MaxPyramid {
public:
    /// Along an axis that wraps (the source's edges), the last cell joins the last sample to the
    /// first, as the wrapped texture interpolates; along one that clamps it holds the last sample.
    MaxPyramid(ClContext& cl, int width, int height, EdgeMode edges);

    /// Enqueues the whole pyramid of `height` (width x height floats); does not wait.
    void build(const cl::Buffer& height);

    const cl::Buffer& buffer() const { return buffer_; }
    const std::vector<PyramidLevel>& levels() const { return levels_; }
    size_t totalFloats() const;

private:
    ClContext& cl_;
    int width_, height_;
    std::vector<PyramidLevel> levels_;
    cl::Buffer buffer_;
    cl::Kernel cells_, reduce_;
};

} // namespace hfx
