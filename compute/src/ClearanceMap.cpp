#include "hfx/compute/ClearanceMap.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <bit>
#include <vector>

namespace hfx {

ClearanceMap::ClearanceMap(ClContext& cl, int width, int height, EdgeMode edges)
    : cl_(cl), width_(width), height_(height) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384 || !std::has_single_bit(unsigned(width)) ||
        !std::has_single_bit(unsigned(height)))
        throw Error(str("ClearanceMap size must be powers of two in 1..16384, got ", width, "x", height));
    clGuard("creating the clearance map", [&] {
        buffer_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR,
                             size_t(width) * height * sizeof(float));
        kernel_ = cl.kernel("clearance.cl", "clearance_map", edgeOptions(edges));
    });
}

void ClearanceMap::build(const cl::Buffer& heights, const BoundsPyramid& pyramid, const ClearanceLight& light) {
    light.validate();
    const std::vector<PyramidLevel>& levels = pyramid.levels();
    if (levels.front().width != width_ || levels.front().height != height_)
        throw Error(str("ClearanceMap::build: the pyramid is of a ", levels.front().width, "x",
                        levels.front().height, " field, the map ", width_, "x", height_));
    if (heights.getInfo<CL_MEM_SIZE>() < sizeof(float) * size_t(width_) * height_)
        throw Error(str("ClearanceMap::build: the height buffer is smaller than ", width_, "x", height_, " floats"));
    // Texel coordinates: u spans width texels, v height.
    const cl_float2 g{{light.uvPerClimb.x * float(width_), light.uvPerClimb.y * float(height_)}};
    const float slack = light.slack * float(std::max(width_, height_));
    clGuard("ClearanceMap::build", [&] {
        kernel_.setArg(0, heights);
        kernel_.setArg(1, pyramid.buffer()); // level 0 at offset 0
        kernel_.setArg(2, buffer_);
        kernel_.setArg(3, width_);
        kernel_.setArg(4, height_);
        kernel_.setArg(5, g);
        kernel_.setArg(6, light.penumbra);
        kernel_.setArg(7, slack);
        if (!offsets_()) {
            std::vector<cl_int> offsets;
            for (const PyramidLevel& l : levels) offsets.push_back(cl_int(l.offset));
            offsets_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, offsets.size() * sizeof(cl_int),
                                  offsets.data());
        }
        kernel_.setArg(8, offsets_);
        kernel_.setArg(9, int(levels.size()));
        cl_.enqueue(kernel_, cl::NDRange(width_, height_));
    });
}

} // namespace hfx
