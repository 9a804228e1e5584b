#include "hfx/compute/SobelNormals.h"

#include "hfx/core/Error.h"

#include <cmath>

namespace hfx {

void SobelConfig::validate() const {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("SobelConfig size must be in 1..16384, got ", width, "x", height));
    if (!(normalDepth > 0.0f) || !std::isfinite(normalDepth))
        throw Error(str("SobelConfig.normalDepth must be positive and finite, got ", normalDepth));
}

SobelNormals::SobelNormals(ClContext& cl, const SobelConfig& config, void* hostMemory) : cl_(cl), config_(config) {
    config.validate();
    clGuard("creating the Sobel normals", [&] {
        const size_t bytes = sizeof(cl_float4) * size_t(config.width) * config.height;
        output_ = hostMemory ? cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, bytes, hostMemory)
                             : cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, bytes);
        // Four texels per work-item where the rows allow it (the faster kernel), one elsewhere.
        kernel_ = cl.kernel("sobel.cl", config.width % 4 == 0 ? "sobel4" : "sobel", edgeOptions(config.edges));
    });
}

void SobelNormals::run(const cl::Buffer& height) {
    requireBufferBytes(height, sizeof(float) * size_t(config_.width) * config_.height,
                       "SobelNormals::run: height buffer",
                       [&] { return str(config_.width, "x", config_.height, " floats"); });
    clGuard("SobelNormals::run", [&] {
        kernel_.setArg(0, height);
        kernel_.setArg(1, output_);
        kernel_.setArg(2, config_.width);
        kernel_.setArg(3, config_.height);
        kernel_.setArg(4, config_.normalDepth * config_.width);
        kernel_.setArg(5, config_.normalDepth * config_.height);
        const size_t perItem = config_.width % 4 == 0 ? 4 : 1;
        cl_.enqueue(kernel_, cl::NDRange(config_.width / perItem, config_.height));
    });
}

} // namespace hfx
