#pragma once
// Waiting for a GL fence (glFenceSync) from the CPU: what a persistently mapped buffer's writer
// does before it writes memory GL may still be reading.
//
// Thread: the thread whose GL context made the fence.

#include "hfx/core/Gl.h"

namespace hfx {

/// Blocks until `fence` is signalled, then deletes it and sets it to null (no-op when null).
/// Flushes once, then waits in slices: a lost context returns GL_WAIT_FAILED rather than hanging,
/// and that throws hfx::Error naming `what`.
void waitAndDelete(GLsync& fence, const char* what);

} // namespace hfx
