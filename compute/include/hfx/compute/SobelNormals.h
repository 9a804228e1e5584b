#pragma once
// Tangent-space normals of any float height buffer by a 3x3 Sobel filter, written as float4
// (normal.xyz, height) per texel: the layout hfx::SurfaceTextures uploads. The output buffer is
// allocated host-visible (CL_MEM_ALLOC_HOST_PTR) so mapping it for the GL upload costs no copy.
//
// Owns its output buffer and kernel. Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"

namespace hfx {

struct SobelConfig {
    int width = 512;
    int height = 512;
    EdgeMode edges = EdgeMode::Wrap; ///< the source's: neighbours across an edge wrap or clamp
    /// The relief depth in texture units the normals are made for: those of the surface
    /// z = normalDepth * h(u, v). The renderer rescales them to the depth it draws with
    /// (SurfaceTexturesConfig::normalDepth records it), so this is fixed for the filter's life.
    float normalDepth = 0.05f;
    void validate() const;
};

class SobelNormals {
public:
    /// hostMemory: where the output lives (width * height float4 that outlive this object, e.g. a
    /// persistently mapped GL pixel buffer), or null for a host-visible buffer of its own.
    SobelNormals(ClContext& cl, const SobelConfig& config, void* hostMemory = nullptr);

    /// Enqueues the filter over `height` (width x height floats); does not wait.
    void run(const cl::Buffer& height);

    const cl::Buffer& output() const { return output_; }
    const SobelConfig& config() const { return config_; }

private:
    ClContext& cl_;
    SobelConfig config_;
    cl::Buffer output_;
    cl::Kernel kernel_;
};

} // namespace hfx
