#pragma once
// Moves a compute buffer of float4 (normal.xyz, height) into SurfaceTextures: maps the
// host-visible buffer (no read into fresh memory) and uploads from the mapping.
//
// Owns nothing; maps and unmaps the buffer around the upload. Thread: the thread that owns
// both the ClContext and the current GL context.

#include "hfx/compute/ClContext.h"
#include "hfx/compute/MaxPyramid.h"
#include "hfx/compute/SurfacePacker.h"
#include "hfx/core/SurfaceTextures.h"

namespace hfx {

/// Waits for the queue's work on `normalHeight`, then uploads it. The buffer must hold
/// textures.config().width * height float4.
void uploadField(ClContext& cl, const cl::Buffer& normalHeight, SurfaceTextures& textures);

/// Waits for the queue's work on the packer's output, then uploads it as it is (a plain copy).
/// The packer's format and size must be the textures'.
void uploadPacked(ClContext& cl, const SurfacePacker& packer, SurfaceTextures& textures);

/// Waits for the queue's work on the pyramid, then uploads all its levels into the textures'
/// pyramid (which must exist and match its size).
void uploadPyramid(ClContext& cl, const MaxPyramid& pyramid, SurfaceTextures& textures);

/// Waits for the queue's work on `rgba`, then uploads it as the albedo: width * height RGBA8.
void uploadAlbedo(ClContext& cl, const cl::Buffer& rgba, SurfaceTextures& textures);

} // namespace hfx
