#include "hfx/core/Gl.h"

#include "hfx/core/Error.h"

#include <cstdio>

namespace hfx {

void loadGl(GlProcLoader loader) {
    const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
    if (version == 0)
        throw Error("could not load OpenGL entry points: no current context, or the driver "
                    "exposes none (install libosmesa6 or a GL driver)");
    const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    if (major < 4 || (major == 4 && minor < 5))
        throw Error(str("HFX needs an OpenGL 4.5 core context, the driver gave ", major, ".", minor,
                        " (", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                        "); on a machine without GPU use Mesa's OSMesa (libosmesa6)"));
}

namespace detail {
void glCheck(const char* call, const char* file, int line) {
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError())
        std::fprintf(stderr, "%s:%d: GL error 0x%04x after %s\n", file, line, e, call);
}
} // namespace detail

} // namespace hfx
