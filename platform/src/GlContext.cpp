#include "hfx/platform/GlContext.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/Names.h"

#include <cstdio>
#include <cstdlib>

namespace hfx {

namespace {
constexpr NamedValue<GlBackend> kBackends[] = {{GlBackend::Auto, "auto"},
                                               {GlBackend::Egl, "egl"},
                                               {GlBackend::EglDevice, "egl-device"},
                                               {GlBackend::EglSurfaceless, "egl-surfaceless"},
                                               {GlBackend::OsMesa, "osmesa"}};

/// The loader whose entry points the process-wide table holds now.
GlProcLoader loadedWith = nullptr;
} // namespace

const char* glBackendName(GlBackend backend) { return nameOf(kBackends, backend); }
GlBackend parseGlBackend(std::string_view name) { return parseName(kBackends, name, "GL backend"); }
std::string glBackendNames() { return namesOf(kBackends); }

GlBackend resolveGlBackend(GlBackend requested) {
    if (requested != GlBackend::Auto) return requested;
    const char* env = std::getenv("HFX_GL");
    if (!env || !*env) return GlBackend::Auto;
    try {
        return parseGlBackend(env);
    } catch (const Error& e) {
        throw Error(str("HFX_GL: ", e.what()));
    }
}

namespace detail {
bool glEntryPointsFrom(GlProcLoader loader) { return loader == loadedWith; }

void bindGlEntryPoints(GlProcLoader loader) {
    if (loader == loadedWith) return;
    loadedWith = nullptr; // a failed load leaves nothing marked as loaded
    loadGl(loader);
    loadedWith = loader;
}
} // namespace detail

std::string GlContext::description() const {
    auto text = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "?");
    };
    return str(backend(), ": OpenGL ", text(GL_VERSION), ", ", text(GL_RENDERER));
}

std::unique_ptr<GlContext> createHeadlessContext(const GlContextConfig& config) {
    const GlBackend backend = resolveGlBackend(config.backend);
    if (backend == GlBackend::OsMesa) return detail::createOsMesaContext(config);
    if (backend != GlBackend::Auto) return detail::createEglContext(config, backend);
    // Auto: EGL reaches a GPU where one exists and llvmpipe where none does; OSMesa is the
    // fallback for a Mesa without EGL (or an EGL without any platform that gives 4.5 core).
    std::string eglWhy;
    try {
        return detail::createEglContext(config, GlBackend::Egl);
    } catch (const Error& e) {
        eglWhy = e.what();
    }
    try {
        auto context = detail::createOsMesaContext(config);
        std::fprintf(stderr, "hfx: no EGL context (%s); using OSMesa\n", eglWhy.c_str());
        return context;
    } catch (const Error& e) {
        throw Error(str("no off-screen OpenGL 4.5 core context: EGL: ", eglWhy, "; OSMesa: ", e.what()));
    }
}

std::unique_ptr<GlContext> createContext(const GlContextConfig& config, bool preferWindow) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if (preferWindow && resolveGlBackend(config.backend) == GlBackend::Auto &&
        ((display && *display) || (wayland && *wayland))) {
        try {
            return createWindowContext(config);
        } catch (const Error& e) {
            std::fprintf(stderr, "hfx: no window (%s); rendering headless\n", e.what());
        }
    }
    return createHeadlessContext(config);
}

} // namespace hfx
