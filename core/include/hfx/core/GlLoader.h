#pragma once
// Loading GL entry points, without including any GL header (so it can sit beside a platform's
// own GL/gl.h, as OSMesa's header brings in).
//
// Thread: load on the thread whose context is current, once per process.

namespace hfx {

/// A function that resolves GL entry points of the current context (OSMesa, GLFW, or the host
/// engine's own).
using GlProc = void (*)();
using GlProcLoader = GlProc (*)(const char* name);

/// Loads the current context's entry points into the process-wide loader table. Throws
/// hfx::Error when there is none or it is older than OpenGL 4.5 core.
void loadGl(GlProcLoader loader);

} // namespace hfx
