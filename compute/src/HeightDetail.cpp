#include "hfx/compute/HeightDetail.h"

#include "hfx/core/Error.h"

#include <cmath>

namespace hfx {

namespace {
float checkedAmount(float amount) {
    if (!(amount >= 0.0f && amount <= 1.0f))
        throw Error(str("HeightDetail: amount must be in [0, 1], got ", amount));
    return amount;
}
} // namespace

HeightDetail::HeightDetail(ClContext& cl, const NoiseConfig& noise, float amount, float capRows)
    : cl_(cl), noise_(cl, noise), amount_(checkedAmount(amount)), capRows_(capRows) {
    if (!(capRows >= 0.0f && capRows <= 0.5f * float(noise.height)))
        throw Error(str("HeightDetail: capRows must be in [0, ", 0.5f * float(noise.height), "], got ", capRows));
    clGuard("creating the height detail", [&] {
        output_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, size_t(noise.width) * noise.height * sizeof(float));
        kernel_ = cl.kernel("detail.cl", "add_height_detail");
    });
}

void HeightDetail::run(const cl::Buffer& base) {
    const int n = noise_.width() * noise_.height();
    clGuard("HeightDetail::run", [&] {
        kernel_.setArg(0, base);
        kernel_.setArg(1, noise_.buffer());
        kernel_.setArg(2, output_);
        kernel_.setArg(3, amount_);
        kernel_.setArg(4, noise_.width());
        kernel_.setArg(5, noise_.height());
        kernel_.setArg(6, capRows_);
        cl_.enqueue(kernel_, cl::NDRange(size_t(n)));
    });
}

} // namespace hfx
