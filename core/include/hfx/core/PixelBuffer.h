#pragma once
// A GL pixel-unpack buffer mapped once for good (persistent, coherent), so a producer — an
// OpenCL device sharing host memory, or the CPU — writes texels straight into memory that a
// texture upload then reads without a copy of the caller's. A fence after each upload tells
// the producer when GL has finished reading, before it writes the next frame.
//
// Needs GL 4.4 buffer storage (core in the 4.5 contexts HFX makes). Owns the buffer and its
// mapping. Thread: the thread whose GL context is current.

#include "hfx/core/GlObject.h"

#include <cstddef>

namespace hfx {

class SurfaceTextures;

class PixelBuffer {
public:
    explicit PixelBuffer(size_t bytes);
    ~PixelBuffer();
    PixelBuffer(const PixelBuffer&) = delete;
    PixelBuffer& operator=(const PixelBuffer&) = delete;

    /// The mapping: `bytes()` bytes, valid for the buffer's lifetime.
    void* memory() const { return memory_; }
    size_t bytes() const { return bytes_; }
    GLuint id() const { return buffer_.id(); }

    /// Blocks until GL has read what the last upload took from the buffer (no-op when none is
    /// in flight), so the memory may be written again.
    void waitUntilRead();
    /// Uploads the buffer's start as the textures' texels (SurfaceTextures::uploadTexels: the
    /// format's layout) and fences the read. Restores the unpack-buffer binding it found.
    void uploadTexels(SurfaceTextures& textures);

private:
    GlBuffer buffer_;
    size_t bytes_ = 0;
    void* memory_ = nullptr;
    GLsync fence_ = nullptr;
};

} // namespace hfx
