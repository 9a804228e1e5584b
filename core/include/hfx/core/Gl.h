#pragma once
// The one include for OpenGL: the glad loader generated at build time (GL 4.5 core).
//
// Thread: GL calls only on the thread whose context is current.

#include <glad/gl.h>

#include "hfx/core/GlLoader.h"

namespace hfx {
namespace detail {
void glCheck(const char* call, const char* file, int line);
}

} // namespace hfx

#if defined(HFX_GL_DEBUG)
#define HFX_GL_CHECK(call)                                                                         \
    do {                                                                                           \
        call;                                                                                      \
        ::hfx::detail::glCheck(#call, __FILE__, __LINE__);                                         \
    } while (0)
#else
#define HFX_GL_CHECK(call) call
#endif
