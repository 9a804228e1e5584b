#pragma once
// The one include for OpenGL: the glad loader generated at build time (GL 4.5 core).
//
// Thread: GL calls only on the thread whose context is current.

#include <glad/gl.h>

#include "hfx/core/GlLoader.h"

namespace hfx {
/// "GL_INVALID_OPERATION" and so on: the name of a glGetError code.
const char* glErrorName(GLenum error);

namespace detail {
/// Throws hfx::Error naming `call`, where it stands and every GL error pending after it
/// ("GL_INVALID_OPERATION after glBindTexture(...) at Texture.cpp:12"); nothing when none is.
void glCheck(const char* call, const char* file, int line);
} // namespace detail
} // namespace hfx

// HFX_GL_CHECK(call): with the HFX_GL_DEBUG build option (cmake -DHFX_GL_DEBUG=ON; the sanitizer
// build turns it on), polls glGetError after the call and throws naming it; otherwise the call
// alone, at no cost.
#if defined(HFX_GL_DEBUG)
#define HFX_GL_CHECK(call)                                                                         \
    do {                                                                                           \
        call;                                                                                      \
        ::hfx::detail::glCheck(#call, __FILE__, __LINE__);                                         \
    } while (0)
#else
#define HFX_GL_CHECK(call) call
#endif
