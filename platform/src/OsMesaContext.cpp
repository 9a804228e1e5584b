// OSMesa, loaded when first asked for (dlopen): Mesa's libOSMesa brings LLVM (about 100 MB) along,
// which a program that renders through EGL on a GPU must not need to start (scripts/bundle.sh
// leaves it out). Only OSMesa's header here, for its types: it includes the system GL/gl.h,
// which must not meet glad's.
#include <GL/osmesa.h>

#include "hfx/core/Error.h"
#include "hfx/platform/GlContext.h"
#include "hfx/core/GlLoader.h"

#include <dlfcn.h>

#include <string>
#include <type_traits>
#include <vector>

namespace hfx {
namespace {

/// libOSMesa's entry points, resolved once for the process (the library stays loaded).
struct OsMesaLibrary {
    decltype(&::OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&::OSMesaDestroyContext) destroyContext = nullptr;
    decltype(&::OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&::OSMesaGetCurrentContext) getCurrentContext = nullptr;
    decltype(&::OSMesaGetProcAddress) getProcAddress = nullptr;
    std::string error; ///< why it could not be loaded; empty when loaded
};

const OsMesaLibrary& osmesa() {
    static const OsMesaLibrary library = [] {
        OsMesaLibrary l;
        void* handle = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
        if (!handle) handle = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            l.error = str("cannot load libOSMesa.so.8 (", why ? why : "not found",
                          "): install Mesa's OSMesa (apt-get install libosmesa6)");
            return l;
        }
        auto bind = [&](auto& fn, const char* name) {
            fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(handle, name));
            if (!fn && l.error.empty()) l.error = str("libOSMesa has no ", name);
        };
        bind(l.createContextAttribs, "OSMesaCreateContextAttribs");
        bind(l.destroyContext, "OSMesaDestroyContext");
        bind(l.makeCurrent, "OSMesaMakeCurrent");
        bind(l.getCurrentContext, "OSMesaGetCurrentContext");
        bind(l.getProcAddress, "OSMesaGetProcAddress");
        return l;
    }();
    return library;
}

GlProc osmesaProc(const char* name) { return reinterpret_cast<GlProc>(osmesa().getProcAddress(name)); }

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(const GlContextConfig& config)
        : width_(config.width), height_(config.height) {
        if (width_ <= 0 || height_ <= 0)
            throw Error(str("headless context size must be positive, got ", width_, "x", height_));
        if (!osmesa().error.empty()) throw Error(osmesa().error);
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               24,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        context_ = osmesa().createContextAttribs(attribs, nullptr);
        if (!context_)
            throw Error("OSMesa could not create an OpenGL 4.5 core context (needs Mesa's "
                        "llvmpipe: apt-get install libosmesa6)");
        pixels_.resize(static_cast<size_t>(width_) * height_);
        try {
            makeCurrent();
        } catch (...) {
            osmesa().destroyContext(context_);
            throw;
        }
    }
    ~OsMesaContext() override {
        // llvmpipe rasterises behind the caller: let it finish before the context goes (Mesa's
        // exit handler can hang joining a rasteriser thread left inside a scene).
        if (osmesa().getCurrentContext() == context_) {
            using Finish = void (*)();
            if (auto finish = reinterpret_cast<Finish>(osmesaProc("glFinish"))) finish();
        }
        osmesa().destroyContext(context_);
    }

    void makeCurrent() override {
        if (!osmesa().makeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, width_, height_))
            throw Error("OSMesaMakeCurrent failed");
        detail::bindGlEntryPoints(&osmesaProc);
    }
    void swapBuffers() override {}
    bool pollEvents() override { return true; }
    glm::ivec2 framebufferSize() const override { return {width_, height_}; }
    bool headless() const override { return true; }
    std::string backend() const override { return "OSMesa"; }

private:
    int width_, height_;
    std::vector<unsigned> pixels_;
    OSMesaContext context_ = nullptr;
};

} // namespace

std::unique_ptr<GlContext> detail::createOsMesaContext(const GlContextConfig& config) {
    return std::make_unique<OsMesaContext>(config);
}

} // namespace hfx
