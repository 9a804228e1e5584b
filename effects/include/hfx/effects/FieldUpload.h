#pragma once
// Moves a compute buffer of surface texels into SurfaceTextures, by one of two paths:
// - Map: maps the host-visible buffer (no read into fresh memory) and uploads from the mapping;
// - PixelBuffer: the device's buffer lies over a persistently mapped GL pixel buffer's memory
//   (CL_MEM_USE_HOST_PTR), so its kernels write the GL buffer itself and the upload reads it
//   with no copy of HFX's; a fence keeps the next frame's kernels from writing it while GL reads.
// (A third path, cl_khr_gl_sharing with no host copy at all, needs a device that offers it
// and a GL context shared with it; the devices HFX is tested on have none.)
//
// Owns nothing; maps and unmaps the buffer around the upload. Thread: the thread that owns
// both the ClContext and the current GL context.

#include "hfx/compute/ClContext.h"
#include "hfx/compute/MaxPyramid.h"
#include "hfx/core/PixelBuffer.h"
#include "hfx/core/SurfaceTextures.h"

#include <string_view>

namespace hfx {

enum class TransferPath {
    Auto,        ///< PixelBuffer where the device shares host memory with the CPU, else Map
    Map,         ///< device buffer mapped, GL uploads from the mapping (client memory)
    PixelBuffer, ///< device writes a persistently mapped GL pixel buffer, GL uploads from it
};
/// "auto", "map", "pixel-buffer".
const char* transferPathName(TransferPath path);
/// The inverse of transferPathName; throws hfx::Error naming the known paths.
TransferPath parseTransferPath(std::string_view name);
/// The path `requested` resolves to on this device: Auto picks PixelBuffer when the device
/// reports host-unified memory (CPU devices, integrated GPUs: the kernels' writes land in the GL
/// buffer directly), else Map (a discrete GPU writing system memory over the bus would be slow).
TransferPath chooseTransferPath(const ClContext& cl, TransferPath requested);

/// PixelBuffer path: waits for the queue's work on `texels` — a buffer created over
/// `pixels.memory()`, in the textures' format's layout — then uploads from the pixel buffer.
void uploadFromPixelBuffer(ClContext& cl, const cl::Buffer& texels, PixelBuffer& pixels, SurfaceTextures& textures);

/// Waits for the queue's work on `normalHeight`, then uploads it. The buffer must hold
/// textures.config().width * height float4.
void uploadField(ClContext& cl, const cl::Buffer& normalHeight, SurfaceTextures& textures);

/// Waits for the queue's work on `texels`, then uploads them as they are (a plain copy): they
/// must be in the textures' format's layout — a SurfacePacker's output, or float4 for Float32.
void uploadTexels(ClContext& cl, const cl::Buffer& texels, SurfaceTextures& textures);

/// Waits for the queue's work on the pyramid, then uploads all its levels into the textures'
/// pyramid (which must exist and match its size).
void uploadPyramid(ClContext& cl, const MaxPyramid& pyramid, SurfaceTextures& textures);

/// Waits for the queue's work on `rgba`, then uploads it as the albedo: width * height RGBA8.
void uploadAlbedo(ClContext& cl, const cl::Buffer& rgba, SurfaceTextures& textures);

} // namespace hfx
