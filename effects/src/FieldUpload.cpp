#include "hfx/effects/FieldUpload.h"

#include "hfx/core/Error.h"

namespace hfx {

namespace {

/// Maps the first `bytes` of `buffer` for reading (waiting for the queue's work on it), hands
/// the mapping to `upload`, and unmaps whatever happens.
template <typename Upload>
void mapAndUpload(ClContext& cl, const cl::Buffer& buffer, size_t bytes, const char* what, Upload&& upload) {
    cl::CommandQueue& q = cl.queue();
    void* mapped = clGuard(what, [&] { return q.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes); });
    try {
        upload(mapped);
    } catch (...) {
        q.enqueueUnmapMemObject(buffer, mapped);
        throw;
    }
    clGuard(what, [&] { q.enqueueUnmapMemObject(buffer, mapped); });
}

/// Bytes of a buffer of `texelBytes` per texel covering the surface; refuses a smaller buffer.
size_t surfaceBytes(const cl::Buffer& buffer, size_t texelBytes, const SurfaceTextures& textures, const char* what) {
    const size_t bytes = texelBytes * size_t(textures.config().width) * textures.config().height;
    if (buffer.getInfo<CL_MEM_SIZE>() < bytes)
        throw Error(str(what, ": buffer of ", buffer.getInfo<CL_MEM_SIZE>(), " bytes is smaller than the ",
                        textures.config().width, "x", textures.config().height, " surface (", bytes, " bytes)"));
    return bytes;
}

} // namespace

void uploadField(ClContext& cl, const cl::Buffer& normalHeight, SurfaceTextures& textures) {
    mapAndUpload(cl, normalHeight, surfaceBytes(normalHeight, sizeof(cl_float4), textures, "uploadField"), "uploadField",
                 [&](const void* mapped) { textures.upload(static_cast<const float*>(mapped)); });
}

const char* transferPathName(TransferPath path) {
    switch (path) {
    case TransferPath::Auto: return "auto";
    case TransferPath::Map: return "map";
    case TransferPath::PixelBuffer: return "pixel-buffer";
    }
    return "unknown";
}

TransferPath parseTransferPath(std::string_view name) {
    for (TransferPath p : {TransferPath::Auto, TransferPath::Map, TransferPath::PixelBuffer})
        if (name == transferPathName(p)) return p;
    throw Error(str("unknown transfer path '", name, "' (known: auto, map, pixel-buffer)"));
}

TransferPath chooseTransferPath(const ClContext& cl, TransferPath requested) {
    if (requested != TransferPath::Auto) return requested;
    const cl_bool unified = clGuard("asking the device about host memory", [&] {
        return cl.device().getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
    });
    return unified ? TransferPath::PixelBuffer : TransferPath::Map;
}

void uploadFromPixelBuffer(ClContext& cl, const cl::Buffer& texels, PixelBuffer& pixels, SurfaceTextures& textures) {
    const size_t bytes = surfaceBytes(texels, texelBytes(textures.config().format), textures, "uploadFromPixelBuffer");
    if (bytes > pixels.bytes())
        throw Error(str("uploadFromPixelBuffer: the pixel buffer holds ", pixels.bytes(), " bytes, the surface needs ", bytes));
    // Mapping a buffer over host memory waits for its writers and makes that memory current
    // (on a device sharing host memory it copies nothing); GL then reads it where it lies.
    mapAndUpload(cl, texels, bytes, "uploadFromPixelBuffer", [&](const void* mapped) {
        if (mapped != pixels.memory())
            throw Error("uploadFromPixelBuffer: the device buffer does not lie over the pixel buffer's memory");
        pixels.uploadSurface(textures);
    });
}

void uploadTexels(ClContext& cl, const cl::Buffer& texels, SurfaceTextures& textures) {
    mapAndUpload(cl, texels, surfaceBytes(texels, texelBytes(textures.config().format), textures, "uploadTexels"),
                 "uploadTexels", [&](const void* mapped) { textures.uploadPacked(mapped); });
}

void uploadPyramid(ClContext& cl, const MaxPyramid& pyramid, SurfaceTextures& textures) {
    if (!textures.pyramid()) throw Error("uploadPyramid: the surface textures have no pyramid");
    const PyramidLevel& base = pyramid.levels().front();
    if (base.width != textures.config().width || base.height != textures.config().height ||
        int(pyramid.levels().size()) != textures.pyramidLevels())
        throw Error(str("uploadPyramid: a ", base.width, "x", base.height, " pyramid of ", pyramid.levels().size(),
                        " levels does not fit the ", textures.config().width, "x", textures.config().height,
                        " surface's ", textures.pyramidLevels()));
    mapAndUpload(cl, pyramid.buffer(), pyramid.totalFloats() * sizeof(float), "uploadPyramid",
                 [&](const void* mapped) { textures.uploadPyramid(static_cast<const float*>(mapped)); });
}

void uploadAlbedo(ClContext& cl, const cl::Buffer& rgba, SurfaceTextures& textures) {
    mapAndUpload(cl, rgba, surfaceBytes(rgba, sizeof(cl_uchar4), textures, "uploadAlbedo"), "uploadAlbedo",
                 [&](const void* mapped) { textures.uploadAlbedo(static_cast<const unsigned char*>(mapped)); });
}

} // namespace hfx
