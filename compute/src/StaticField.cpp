#include "hfx/compute/StaticField.h"

#include "hfx/core/Error.h"

#include <cmath>

namespace hfx {

namespace {
const std::vector<float>& checked(int width, int height, const std::vector<float>& heights) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("StaticField size must be in 1..16384, got ", width, "x", height));
    if (heights.size() != size_t(width) * height)
        throw Error(str("StaticField: ", heights.size(), " heights do not make a ", width, "x", height, " field"));
    for (size_t i = 0; i < heights.size(); ++i)
        if (!(heights[i] >= 0.0f && heights[i] <= 1.0f))
            throw Error(str("StaticField: height ", heights[i], " at texel (", i % width, ", ", i / width,
                            ") is outside [0, 1]"));
    return heights;
}
} // namespace

StaticField::StaticField(ClContext& cl, int width, int height, EdgeMode edges, const std::vector<float>& heights)
    : width_(width), rows_(height), edges_(edges) {
    const std::vector<float>& h = checked(width, height, heights);
    height_ = clGuard("uploading the static heights", [&] {
        return cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, h.size() * sizeof(float),
                          const_cast<float*>(h.data()));
    });
}

void StaticField::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("StaticField::step: dt must be positive and finite, got ", dt));
}

} // namespace hfx
