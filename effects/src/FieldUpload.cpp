#include "hfx/effects/FieldUpload.h"

#include "hfx/core/Error.h"

namespace hfx {

void uploadField(ClContext& cl, const cl::Buffer& normalHeight, SurfaceTextures& textures) {
    const size_t bytes = sizeof(cl_float4) * size_t(textures.config().width) * textures.config().height;
    if (normalHeight.getInfo<CL_MEM_SIZE>() < bytes)
        throw Error(str("uploadField: buffer of ", normalHeight.getInfo<CL_MEM_SIZE>(),
                        " bytes is smaller than the ", textures.config().width, "x",
                        textures.config().height, " surface (", bytes, " bytes)"));
    cl::CommandQueue& q = cl.queue();
    void* mapped = clGuard("mapping the field for upload", [&] {
        return q.enqueueMapBuffer(normalHeight, CL_TRUE, CL_MAP_READ, 0, bytes);
    });
    try {
        textures.upload(static_cast<const float*>(mapped));
    } catch (...) {
        q.enqueueUnmapMemObject(normalHeight, mapped);
        throw;
    }
    clGuard("unmapping the field", [&] { q.enqueueUnmapMemObject(normalHeight, mapped); });
}

} // namespace hfx
