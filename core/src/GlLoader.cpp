#include "hfx/core/Gl.h"

#include "hfx/core/Error.h"

#include <string>

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

const char* glErrorName(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    default: return "GL error";
    }
}

namespace detail {
void glCheck(const char* call, const char* file, int line) {
    std::string errors;
    // A lost context reports errors forever: a bounded number is enough to name them.
    for (int i = 0; i < 8; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        errors += str(errors.empty() ? "" : ", ", glErrorName(e), " (0x", std::hex, e, std::dec, ")");
    }
    if (!errors.empty()) throw Error(str(errors, " after ", call, " at ", sourceName(file), ":", line));
}
} // namespace detail

} // namespace hfx
