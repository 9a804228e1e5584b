#include "hfx/compute/DetailNormals.h"

#include "hfx/core/Error.h"

namespace hfx {

namespace {
const SobelConfig& checked(const SobelConfig& sobel, const std::vector<float>& baseHeights,
                           const std::vector<float>& detail) {
    sobel.validate();
    const size_t texels = size_t(sobel.width) * sobel.height;
    if (baseHeights.size() != texels || detail.size() != texels * 4)
        throw Error(str("DetailNormals: a ", sobel.width, "x", sobel.height, " surface needs ", texels,
                        " base heights and ", texels * 4, " detail floats, got ", baseHeights.size(), " and ",
                        detail.size()));
    return sobel;
}
} // namespace

DetailNormals::DetailNormals(ClContext& cl, const SobelConfig& sobel, const std::vector<float>& baseHeights,
                             const std::vector<float>& detail)
    : cl_(cl), count_(checked(sobel, baseHeights, detail).width * sobel.height), baseNormals_(cl, sobel) {
    clGuard("creating the detail normals", [&] {
        const cl::Buffer base(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                              baseHeights.size() * sizeof(float), const_cast<float*>(baseHeights.data()));
        detail_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, detail.size() * sizeof(float),
                             const_cast<float*>(detail.data()));
        kernel_ = cl.kernel("detail.cl", "add_detail");
        baseNormals_.run(base); // the in-order queue runs it before any apply(); the buffer lives on by reference
    });
}

void DetailNormals::apply(const cl::Buffer& normals) {
    requireBufferBytes(normals, size_t(count_) * sizeof(cl_float4), "DetailNormals::apply: the normals buffer",
                       [&] { return str(count_, " float4 texels"); });
    clGuard("DetailNormals::apply", [&] {
        kernel_.setArg(0, normals);
        kernel_.setArg(1, baseNormals_.output());
        kernel_.setArg(2, detail_);
        kernel_.setArg(3, count_);
        cl_.enqueue(kernel_, cl::NDRange(size_t(count_)));
    });
}

} // namespace hfx
