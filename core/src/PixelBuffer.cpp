#include "hfx/core/PixelBuffer.h"

#include "hfx/core/Error.h"
#include "hfx/core/GlFence.h"
#include "hfx/core/SurfaceTextures.h"

namespace hfx {

namespace {
constexpr GLbitfield kMapping = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
}

PixelBuffer::PixelBuffer(size_t bytes) : buffer_(GlBuffer::create()), bytes_(bytes) {
    if (bytes == 0) throw Error("PixelBuffer: zero bytes requested");
    HFX_GL_CHECK(glNamedBufferStorage(buffer_.id(), GLsizeiptr(bytes), nullptr, kMapping));
    memory_ = glMapNamedBufferRange(buffer_.id(), 0, GLsizeiptr(bytes), kMapping);
    if (!memory_)
        throw Error(str("PixelBuffer: mapping a ", bytes, "-byte pixel buffer persistently failed (GL error 0x",
                        std::hex, glGetError(), "); the driver needs GL 4.4 buffer storage"));
}

PixelBuffer::~PixelBuffer() {
    if (fence_) glDeleteSync(fence_);
    if (memory_ && buffer_.id()) glUnmapNamedBuffer(buffer_.id());
}

void PixelBuffer::waitUntilRead() { waitAndDelete(fence_, "the pixel buffer"); }

void PixelBuffer::uploadTexels(SurfaceTextures& textures) {
    const auto& c = textures.config();
    const size_t needed = size_t(c.width) * c.height * texelBytes(c.format);
    if (needed > bytes_)
        throw Error(str("PixelBuffer: a ", c.width, "x", c.height, " surface needs ", needed, " bytes, the buffer holds ",
                        bytes_));
    waitUntilRead(); // never two reads in flight
    GLint previous = 0;
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &previous);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer_.id());
    textures.uploadTexels(nullptr); // with an unpack buffer bound, the pointer is the offset into it
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(previous));
    fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

} // namespace hfx
