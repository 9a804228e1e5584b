#include "hfx/compute/BoundsPyramid.h"

#include "hfx/core/Error.h"

namespace hfx {

BoundsPyramid::BoundsPyramid(ClContext& cl, int width, int height, EdgeMode edges)
    : cl_(cl), width_(width), height_(height) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("BoundsPyramid size must be in 1..16384, got ", width, "x", height));
    size_t offset = 0;
    for (int w = width, h = height;; w = (w + 1) / 2, h = (h + 1) / 2) {
        levels_.push_back({w, h, offset});
        offset += size_t(w) * h;
        if (w == 1 && h == 1) break;
    }
    clGuard("creating the height-bounds pyramid", [&] {
        buffer_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR,
                             offset * 2 * sizeof(float));
        const std::string options = edgeOptions(edges);
        cells_ = cl.kernel("pyramid.cl", "bounds_cells", options);
        reduce_ = cl.kernel("pyramid.cl", "bounds_reduce", options);
    });
}

size_t BoundsPyramid::totalTexels() const {
    const PyramidLevel& last = levels_.back();
    return last.offset + size_t(last.width) * last.height;
}

void BoundsPyramid::build(const cl::Buffer& height) {
    requireBufferBytes(height, sizeof(float) * size_t(width_) * height_, "BoundsPyramid::build: the height buffer",
                       [&] { return str(width_, "x", height_, " floats"); });
    clGuard("BoundsPyramid::build", [&] {
        cells_.setArg(0, height);
        cells_.setArg(1, buffer_); // level 0 starts at offset 0
        cells_.setArg(2, width_);
        cells_.setArg(3, height_);
        cl_.enqueue(cells_, cl::NDRange(width_, height_));
        for (size_t k = 1; k < levels_.size(); ++k) {
            reduce_.setArg(0, buffer_);
            reduce_.setArg(1, int(levels_[k - 1].offset));
            reduce_.setArg(2, levels_[k - 1].width);
            reduce_.setArg(3, levels_[k - 1].height);
            reduce_.setArg(4, int(levels_[k].offset));
            reduce_.setArg(5, levels_[k].width);
            reduce_.setArg(6, levels_[k].height);
            cl_.enqueue(reduce_, cl::NDRange(levels_[k].width, levels_[k].height));
        }
    });
}

} // namespace hfx
