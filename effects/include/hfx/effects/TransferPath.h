#pragma once
// How a surface's texels travel from the compute device to GL (SurfacePipeline moves them):
// - Map: maps the host-visible device buffer (no read into fresh memory) and uploads from the
//   mapping;
// - PixelBuffer: the device's buffer lies over a persistently mapped GL pixel buffer's memory
//   (CL_MEM_USE_HOST_PTR), so its kernels write the GL buffer itself and the upload reads it
//   with no copy of HFX's; a fence keeps the next frame's kernels from writing it while GL reads.
// (A third path, cl_khr_gl_sharing with no host copy at all, needs a device that offers it and a
// GL context shared with it; the devices HFX is tested on have none.)
//
// Thread: any (chooseTransferPath asks the device).

#include "hfx/compute/ClContext.h"

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

} // namespace hfx
