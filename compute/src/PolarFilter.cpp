#include "hfx/compute/PolarFilter.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>

namespace hfx {

float PolarFilter::rowWidth(int y, int width, int height, float smoothing) {
    const double latitude = ((y + 0.5) / height - 0.5) * 3.141592653589793;
    const double stretch = 1.0 / std::max(std::cos(latitude), 1e-9) - 1.0; // 1 at 60 degrees
    return float(std::min(double(smoothing) / 360.0 * width * stretch * stretch, double(width)));
}

std::vector<float> PolarFilter::reference(const std::vector<float>& field, int width, int height, float smoothing) {
    std::vector<float> widths(size_t(std::max(height, 0)));
    for (int y = 0; y < height; ++y) widths[size_t(y)] = rowWidth(y, width, height, smoothing);
    return reference(field, width, height, widths);
}

std::vector<float> PolarFilter::reference(const std::vector<float>& field, int width, int height,
                                          const std::vector<float>& widths) {
    if (width < 1 || height < 1 || field.size() != size_t(width) * size_t(height) || widths.size() != size_t(height))
        throw Error(str("PolarFilter::reference: ", field.size(), " values for ", width, "x", height, " and ",
                        widths.size(), " row widths"));
    std::vector<float> out(field);
    for (int y = 0; y < height; ++y) {
        const double w = widths[size_t(y)];
        if (w <= 1.0) continue;
        const float* row = field.data() + size_t(y) * width;
        std::vector<double> prefix(size_t(width) + 1, 0.0); // the sums of the texels before each
        for (int i = 0; i < width; ++i) prefix[size_t(i) + 1] = prefix[size_t(i)] + row[i];
        // The integral of the piecewise-constant row (texel i on [i, i + 1)) from 0 to t.
        auto integral = [&](double t) {
            const double turns = std::floor(t / width), local = t - turns * width;
            const int i = std::min(int(local), width - 1);
            return turns * prefix[size_t(width)] + prefix[size_t(i)] + (local - i) * row[i];
        };
        for (int x = 0; x < width; ++x)
            out[size_t(y) * width + x] = float((integral(x + 0.5 + 0.5 * w) - integral(x + 0.5 - 0.5 * w)) / w);
    }
    return out;
}

namespace {
void checkSize(int width, int height) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("PolarFilter size must be in 1..16384, got ", width, "x", height));
}

std::vector<float> widthsOf(int width, int height, float smoothing) {
    checkSize(width, height);
    if (!(smoothing >= 0.0f && smoothing <= 60.0f))
        throw Error(str("PolarFilter smoothing must be in [0, 60] degrees of longitude, got ", smoothing));
    std::vector<float> widths(static_cast<size_t>(height));
    for (int y = 0; y < height; ++y) widths[size_t(y)] = PolarFilter::rowWidth(y, width, height, smoothing);
    return widths;
}
} // namespace

PolarFilter::PolarFilter(ClContext& cl, int width, int height, float smoothing)
    : PolarFilter(cl, width, height, widthsOf(width, height, smoothing)) {
    smoothing_ = smoothing;
}

PolarFilter::PolarFilter(ClContext& cl, int width, int height, const std::vector<float>& widths)
    : cl_(cl), width_(width), height_(height), smoothing_(0.0f) {
    checkSize(width, height);
    if (widths.size() != size_t(height))
        throw Error(str("PolarFilter: ", widths.size(), " row widths for ", height, " rows"));
    for (size_t y = 0; y < widths.size(); ++y)
        if (!(widths[y] >= 0.0f && widths[y] <= float(width)))
            throw Error(str("PolarFilter: row ", y, "'s width must be in [0, ", width, "] texels, got ", widths[y]));
    clGuard("creating the polar filter", [&] {
        prefix_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, sizeof(float) * size_t(width + 1) * height);
        widths_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * widths.size(),
                             const_cast<float*>(widths.data())); // CL_MEM_COPY_HOST_PTR only reads it
        sums_ = cl.kernel("polar.cl", "polar_sums");
        filter_ = cl.kernel("polar.cl", "polar_filter");
    });
}

void PolarFilter::run(const cl::Buffer& field) {
    if (!output_())
        clGuard("creating the polar filter's output", [&] {
            output_ = cl::Buffer(cl_.context(), CL_MEM_READ_WRITE, sizeof(float) * size_t(width_) * height_);
        });
    run(field, output_);
}

void PolarFilter::run(const cl::Buffer& field, const cl::Buffer& out) {
    const auto floats = [&] { return str(width_, "x", height_, " floats"); };
    requireBufferBytes(field, sizeof(float) * size_t(width_) * height_, "PolarFilter::run: field", floats);
    requireBufferBytes(out, sizeof(float) * size_t(width_) * height_, "PolarFilter::run: out", floats);
    if (out() == field()) throw Error("PolarFilter::run: out is the field it reads; give it another buffer");
    clGuard("PolarFilter::run", [&] {
        setArgs(sums_, field, prefix_, widths_, width_, height_);
        cl_.enqueue(sums_, cl::NDRange(size_t(height_)));
        setArgs(filter_, field, prefix_, widths_, out, width_, height_);
        cl_.enqueue(filter_, cl::NDRange(size_t(width_), size_t(height_)));
    });
}

} // namespace hfx
