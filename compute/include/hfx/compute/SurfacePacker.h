#pragma once
// Packs float4 (normal.xyz, height) texels, as SobelNormals writes them, into the layout of a
// smaller SurfaceFormat (half4 or RGBA8) on the device, so the frame's transfer to GL moves 8 or
// 4 bytes a texel instead of 16 and SurfaceTextures::uploadPacked copies it as it is.
// For Float32 there is nothing to pack: run() refuses, use the float4 buffer itself.
//
// Owns its output buffer (host-visible, CL_MEM_ALLOC_HOST_PTR, or the caller's memory) and
// kernel. Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"
#include "hfx/core/SurfaceFormat.h"

namespace hfx {

class SurfacePacker {
public:
    /// hostMemory: where the packed texels live (width * height * texelBytes(format) bytes that
    /// outlive the packer, e.g. a persistently mapped GL pixel buffer), or null for a buffer of
    /// the packer's own.
    SurfacePacker(ClContext& cl, int width, int height, SurfaceFormat format, void* hostMemory = nullptr);

    /// Enqueues the packing of `normalHeight` (width * height float4); does not wait.
    void run(const cl::Buffer& normalHeight);

    const cl::Buffer& output() const { return output_; }
    SurfaceFormat format() const { return format_; }
    size_t bytes() const { return bytes_; }

private:
    ClContext& cl_;
    int count_;
    SurfaceFormat format_;
    size_t bytes_;
    cl::Buffer output_;
    cl::Kernel kernel_;
};

} // namespace hfx
