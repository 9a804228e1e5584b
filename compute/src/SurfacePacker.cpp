#include "hfx/compute/SurfacePacker.h"

#include "hfx/core/Error.h"

namespace hfx {

SurfacePacker::SurfacePacker(ClContext& cl, int width, int height, SurfaceFormat format, void* hostMemory)
    : cl_(cl), count_(width * height), format_(format) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw Error(str("SurfacePacker size must be in 1..16384, got ", width, "x", height));
    if (format == SurfaceFormat::Float32)
        throw Error("SurfacePacker: float32 surfaces need no packing (upload the float4 buffer itself)");
    bytes_ = size_t(count_) * texelBytes(format);
    clGuard("creating the surface packer", [&] {
        output_ = hostMemory ? cl::Buffer(cl.context(), CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR, bytes_, hostMemory)
                             : cl::Buffer(cl.context(), CL_MEM_WRITE_ONLY | CL_MEM_ALLOC_HOST_PTR, bytes_);
        kernel_ = cl.kernel("pack.cl", format == SurfaceFormat::Float16 ? "pack_half" : "pack_unorm8");
    });
}

void SurfacePacker::run(const cl::Buffer& normalHeight) {
    requireBufferBytes(normalHeight, size_t(count_) * sizeof(cl_float4), "SurfacePacker::run: input",
                       [&] { return str(count_, " float4 texels"); });
    clGuard("SurfacePacker::run", [&] {
        kernel_.setArg(0, normalHeight);
        kernel_.setArg(1, output_);
        kernel_.setArg(2, count_);
        cl_.enqueue(kernel_, cl::NDRange(size_t(count_)));
    });
}

} // namespace hfx
