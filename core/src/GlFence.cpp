#include "hfx/core/GlFence.h"

#include "hfx/core/Error.h"

namespace hfx {

void waitAndDelete(GLsync& fence, const char* what) {
    if (!fence) return;
    GLbitfield flags = GL_SYNC_FLUSH_COMMANDS_BIT;
    for (;;) {
        const GLenum r = glClientWaitSync(fence, flags, 100'000'000); // 100 ms
        if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) break;
        if (r == GL_WAIT_FAILED) throw Error(str("waiting for GL to read ", what, " failed"));
        flags = 0;
    }
    glDeleteSync(fence);
    fence = nullptr;
}

GlFence::~GlFence() {
    if (sync_) glDeleteSync(sync_);
}

GlFence::GlFence(GlFence&& other) noexcept : sync_(other.sync_) { other.sync_ = nullptr; }

GlFence& GlFence::operator=(GlFence&& other) noexcept {
    if (this != &other) {
        if (sync_) glDeleteSync(sync_);
        sync_ = other.sync_;
        other.sync_ = nullptr;
    }
    return *this;
}

GlFence GlFence::insert() {
    GlFence f;
    f.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!f.sync_) throw Error("glFenceSync made no fence");
    return f;
}

bool GlFence::done() const {
    if (!sync_) return false;
    const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}

} // namespace hfx
