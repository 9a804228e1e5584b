#include "hfx/compute/ColorRamp.h"

#include "hfx/core/Error.h"

#include <cmath>

namespace hfx {
namespace {
constexpr int kMaxStops = 64;

void validate(const std::vector<ColorStop>& stops) {
    if (stops.size() < 2 || stops.size() > kMaxStops)
        throw Error(str("ColorRamp needs 2 to ", kMaxStops, " stops, got ", stops.size()));
    for (size_t i = 0; i < stops.size(); ++i) {
        const ColorStop& s = stops[i];
        if (!(s.position >= 0.0f && s.position <= 1.0f))
            throw Error(str("ColorRamp stop ", i, ": position must be in [0, 1], got ", s.position));
        if (i > 0 && !(s.position > stops[i - 1].position))
            throw Error(str("ColorRamp stop ", i, ": positions must rise, got ", s.position, " after ",
                            stops[i - 1].position));
        for (int c = 0; c < 3; ++c)
            if (!(s.color[c] >= 0.0f && s.color[c] <= 1.0f))
                throw Error(str("ColorRamp stop ", i, ": colour channels must be in [0, 1], got ", s.color[c]));
    }
}
} // namespace

std::vector<float> ColorRamp::pack(const std::vector<ColorStop>& stops) {
    std::vector<float> packed;
    for (const ColorStop& s : stops) packed.insert(packed.end(), {s.position, s.color.r, s.color.g, s.color.b});
    return packed;
}

ColorRamp::ColorRamp(ClContext& cl, int width, int height, std::vector<ColorStop> stops)
    : cl_(cl), width_(width), height_(height) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("ColorRamp size must be in 1..16384, got ", width, "x", height));
    clGuard("creating the colour ramp", [&] {
        output_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR,
                             sizeof(cl_uchar4) * size_t(width) * height);
        stopBuffer_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY, sizeof(float) * 4 * kMaxStops);
        kernel_ = cl.kernel("colorize.cl", "colorize");
    });
    setStops(std::move(stops));
}

void ColorRamp::setStops(std::vector<ColorStop> stops) {
    validate(stops);
    const std::vector<float> packed = pack(stops);
    clGuard("uploading the colour stops", [&] {
        cl_.queue().enqueueWriteBuffer(stopBuffer_, CL_TRUE, 0, packed.size() * sizeof(float), packed.data());
    });
    stops_ = std::move(stops);
}

void ColorRamp::run(const cl::Buffer& field) {
    const size_t n = size_t(width_) * height_;
    requireBufferBytes(field, n * sizeof(float), "ColorRamp::run: field",
                       [&] { return str(width_, "x", height_, " floats"); });
    clGuard("ColorRamp::run", [&] {
        kernel_.setArg(0, field);
        kernel_.setArg(1, output_);
        kernel_.setArg(2, stopBuffer_);
        kernel_.setArg(3, int(stops_.size()));
        kernel_.setArg(4, int(n));
        cl_.enqueue(kernel_, cl::NDRange(n));
    });
}

} // namespace hfx
