#pragma once
// Waiting for a GL fence (glFenceSync) from the CPU: what a persistently mapped buffer's writer
// does before it writes memory GL may still be reading; and GlFence, one that is only asked
// whether it is done (feedback read back once the GPU is past it, never waited for).
//
// Thread: the thread whose GL context made the fence.

#include "hfx/core/Gl.h"

namespace hfx {

/// Blocks until `fence` is signalled, then deletes it and sets it to null (no-op when null).
/// Flushes once, then waits in slices: a lost context returns GL_WAIT_FAILED rather than hanging,
/// and that throws hfx::Error naming `what`.
void waitAndDelete(GLsync& fence, const char* what);

/// Owns a fence put after the commands submitted so far; empty by default.
class GlFence {
public:
    GlFence() = default;
    ~GlFence();
    GlFence(GlFence&& other) noexcept;
    GlFence& operator=(GlFence&& other) noexcept;
    GlFence(const GlFence&) = delete;
    GlFence& operator=(const GlFence&) = delete;

    /// A fence after every command submitted so far.
    static GlFence insert();
    /// Whether GL has run every command before the fence (flushes them; never waits). False
    /// when empty.
    bool done() const;
    explicit operator bool() const { return sync_ != nullptr; }

private:
    GLsync sync_ = nullptr;
};

} // namespace hfx
