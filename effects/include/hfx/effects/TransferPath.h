#pragma once
// How a surface's texels (and on llvmpipe its pyramid, its albedo and shading channels) travel from
// the compute device to GL (SurfacePipeline moves them):
// - Map: maps the device buffer and uploads from the mapping (client memory): the plain path;
// - PixelBuffer: the device's buffer lies over a persistently mapped GL pixel buffer's memory
//   (CL_MEM_USE_HOST_PTR), so its kernels write the GL buffer itself and the upload reads it
//   with no copy of HFX's; a fence keeps the next frame's kernels from writing it while GL
//   reads. For a device that shares host memory (a CPU device, an integrated GPU);
// - Staged: a non-blocking read into pinned host memory (CL_MEM_ALLOC_HOST_PTR), copied into a
//   persistently mapped, fenced two-slot GL pixel buffer, uploaded from there; the read overlaps
//   the host's work until finish(). For a discrete GPU (a map of its memory moved 0.3 GB/s on an
//   H200; pinned memory moves 10+);
// - GlSharing: cl_khr_gl_sharing, the device copies into GL buffers it shares with the caller's
//   context (ClContext::sharesGl(): NVIDIA offers it for GLX contexts, not EGL); no host copy;
// - ExternalMemory: the device copies into memory that Vulkan allocates on GL's device and both
//   GL and the device import (GL_EXT_memory_object_fd; cl_khr_external_memory_opaque_fd, which
//   NVIDIA's recent OpenCL drivers list, or a CPU device over the memory's mapping); no host
//   copy, for any GL context, EGL's included. Vulkan is loaded at run time (libvulkan.so.1). Auto's
//   choice for a discrete GPU where it is offered: an H200 moved the water's texels 1.3-4.0x
//   faster that way than Staged, in every format (docs/BENCHMARKS.md).
// (StreamTransfer.h in effects/src holds the last three, ExternalMemory.h the allocator.)
//
// Thread: the thread whose GL context is current (chooseTransferPath and transferPathRefusal ask
// the device, and for ExternalMemory GL and Vulkan).

#include "hfx/compute/ClContext.h"

#include <string>
#include <string_view>
#include <vector>

namespace hfx {

enum class TransferPath {
    Auto,        ///< GlSharing where the context shares GL, PixelBuffer where the device shares host memory,
                 ///< else ExternalMemory where offered, else Staged
    Map,         ///< device buffer mapped, GL uploads from the mapping (client memory)
    PixelBuffer, ///< device writes a persistently mapped GL pixel buffer, GL uploads from it
    Staged,      ///< non-blocking read into pinned memory, copied into a fenced GL pixel-buffer ring
    GlSharing,   ///< the device copies into GL buffers shared through cl_khr_gl_sharing
    ExternalMemory, ///< the device copies into memory Vulkan allocates and GL and the device import
};
/// "auto", "map", "pixel-buffer", "staged", "gl-sharing", "external-memory".
const char* transferPathName(TransferPath path);
/// The inverse of transferPathName; throws hfx::Error naming the known paths.
TransferPath parseTransferPath(std::string_view name);
/// The path `requested` resolves to on this device: Auto picks GlSharing when the CL context
/// shares the GL context (no host copy), else PixelBuffer when the device reports host-unified
/// memory (CPU devices, integrated GPUs: the kernels' writes land in the GL buffer directly),
/// else (a discrete GPU) ExternalMemory where GL, Vulkan and the device can share memory (no host
/// copy), else Staged (pinned memory at the bus's speed). Asking for GlSharing where the
/// context shares none, or for ExternalMemory where the machine lacks a part of it, throws
/// hfx::Error saying what is missing.
TransferPath chooseTransferPath(const ClContext& cl, TransferPath requested);
/// The paths this device can take (Auto left out): GlSharing only where the context shares GL,
/// ExternalMemory only where GL, Vulkan and the device can share memory.
std::vector<TransferPath> availableTransferPaths(const ClContext& cl);
/// Why `path` cannot be taken here, in the words chooseTransferPath throws ("" where it can: Auto,
/// Map, PixelBuffer and Staged always can). For a settings menu that shows each path's reason.
std::string transferPathRefusal(const ClContext& cl, TransferPath path);

} // namespace hfx
