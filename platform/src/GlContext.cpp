#include "hfx/platform/GlContext.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"

#include <cstdio>
#include <cstdlib>

namespace hfx {

std::string GlContext::description() const {
    auto text = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "?");
    };
    return str("OpenGL ", text(GL_VERSION), ", ", text(GL_RENDERER));
}

std::unique_ptr<GlContext> createContext(const GlContextConfig& config, bool preferWindow) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if (preferWindow && ((display && *display) || (wayland && *wayland))) {
        try {
            return createWindowContext(config);
        } catch (const Error& e) {
            std::fprintf(stderr, "hfx: no window (%s); rendering headless\n", e.what());
        }
    }
    return createHeadlessContext(config);
}

} // namespace hfx
