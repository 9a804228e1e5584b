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

} // namespace hfx
