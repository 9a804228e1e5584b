// Off-screen GL 4.5 core through EGL: the device platform (EGL_EXT_platform_device: a GPU's
// driver, or Mesa's software device) and Mesa's surfaceless platform. Only EGL's headers here:
// they must not meet glad's GL header.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "hfx/core/Error.h"
#include "hfx/platform/GlContext.h"

#include <map>
#include <string>
#include <vector>

namespace hfx {
namespace {

GlProc eglProc(const char* name) { return reinterpret_cast<GlProc>(eglGetProcAddress(name)); }

std::string eglErrorName(EGLint code) {
    switch (code) {
#define HFX_CASE(c) case c: return #c
        HFX_CASE(EGL_NOT_INITIALIZED);
        HFX_CASE(EGL_BAD_ACCESS);
        HFX_CASE(EGL_BAD_ALLOC);
        HFX_CASE(EGL_BAD_ATTRIBUTE);
        HFX_CASE(EGL_BAD_CONFIG);
        HFX_CASE(EGL_BAD_CONTEXT);
        HFX_CASE(EGL_BAD_CURRENT_SURFACE);
        HFX_CASE(EGL_BAD_DISPLAY);
        HFX_CASE(EGL_BAD_MATCH);
        HFX_CASE(EGL_BAD_PARAMETER);
        HFX_CASE(EGL_BAD_SURFACE);
#undef HFX_CASE
    default: return str("EGL error 0x", std::hex, code);
    }
}

/// "what failed with EGL_BAD_MATCH": the thread's last EGL error.
std::string eglFailure(const char* what) { return str(what, " failed with ", eglErrorName(eglGetError())); }

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::string all = str(" ", list, " ");
    return all.find(str(" ", name, " ")) != std::string::npos;
}

/// EGL initialises a display once for the process, not once per caller: eglTerminate would
/// end it under every other context on it. Counted here, terminated with its last context.
std::map<EGLDisplay, int>& displayUsers() {
    static std::map<EGLDisplay, int> users;
    return users;
}

void acquireDisplay(EGLDisplay display) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) throw Error(eglFailure("eglInitialize"));
    ++displayUsers()[display];
}

void releaseDisplay(EGLDisplay display) {
    auto it = displayUsers().find(display);
    if (it == displayUsers().end() || --it->second > 0) return;
    displayUsers().erase(it);
    eglTerminate(display);
}

struct EglEntryPoints {
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC platformDisplay = nullptr;
};

EglEntryPoints entryPoints() {
    return {reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT")),
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT")),
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"))};
}

/// One place a display can come from, in the order tried.
struct Candidate {
    EGLDisplay display = EGL_NO_DISPLAY;
    std::string label; ///< "EGL device 'NVIDIA' (...)", "EGL surfaceless"
};

/// The device platform's displays: hardware devices first, then software ones (Mesa's llvmpipe
/// device, present with or without a GPU).
std::vector<Candidate> deviceCandidates(const EglEntryPoints& egl, bool software, std::string& why) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(client, "EGL_EXT_platform_device") || !egl.queryDevices || !egl.platformDisplay) {
        why += "; no EGL_EXT_platform_device";
        return {};
    }
    EGLint count = 0;
    if (!egl.queryDevices(0, nullptr, &count) || count <= 0) {
        why += "; EGL_EXT_platform_device lists no device";
        return {};
    }
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
    egl.queryDevices(count, devices.data(), &count);
    std::vector<Candidate> out;
    for (EGLint i = 0; i < count; ++i) {
        const char* extensions = egl.queryDeviceString ? egl.queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
        if (hasExtension(extensions, "EGL_MESA_device_software") != software) continue;
        std::string label = software ? "EGL device (Mesa software)" : str("EGL device ", i);
        if (!software && hasExtension(extensions, "EGL_EXT_device_drm")) {
            const char* file = egl.queryDeviceString(devices[i], EGL_DRM_DEVICE_FILE_EXT);
            if (file) label += str(" (", file, ")");
        } else if (!software && hasExtension(extensions, "EGL_NV_device_cuda")) {
            label += " (NVIDIA CUDA device)";
        }
        EGLDisplay display = egl.platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display == EGL_NO_DISPLAY)
            why += str("; ", label, ": ", eglFailure("eglGetPlatformDisplayEXT"));
        else
            out.push_back({display, label});
    }
    return out;
}

std::vector<Candidate> surfacelessCandidate(const EglEntryPoints& egl, std::string& why) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(client, "EGL_MESA_platform_surfaceless") || !egl.platformDisplay) {
        why += "; no EGL_MESA_platform_surfaceless";
        return {};
    }
    EGLDisplay display = egl.platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) {
        why += str("; EGL surfaceless: ", eglFailure("eglGetPlatformDisplayEXT"));
        return {};
    }
    return {{display, "EGL surfaceless"}};
}

class EglContext final : public GlContext {
public:
    /// Makes the context on `display` (initialised by the caller through acquireDisplay, and
    /// released here on failure as on destruction).
    EglContext(const GlContextConfig& config, EGLDisplay display, std::string label)
        : width_(config.width), height_(config.height), display_(display), label_(std::move(label)) {
        try {
            create();
        } catch (...) {
            destroy();
            throw;
        }
    }
    ~EglContext() override {
        // Let a software rasteriser finish before the context goes (llvmpipe's exit handler can
        // hang joining a thread left inside a scene), as the OSMesa context does.
        if (eglGetCurrentContext() == context_) {
            using Finish = void (*)();
            if (auto finish = reinterpret_cast<Finish>(eglGetProcAddress("glFinish"))) finish();
        }
        destroy();
    }

    void makeCurrent() override {
        if (!detail::glEntryPointsFrom(&eglProc)) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (!eglMakeCurrent(display_, surface_, surface_, context_)) throw Error(eglFailure("eglMakeCurrent"));
        detail::bindGlEntryPoints(&eglProc);
    }
    void swapBuffers() override {}
    bool pollEvents() override { return true; }
    glm::ivec2 framebufferSize() const override { return {width_, height_}; }
    bool headless() const override { return true; }
    std::string backend() const override { return label_; }
    GlShareHandles shareHandles() const override {
        return {.api = GlShareHandles::Api::Egl, .context = context_, .display = display_};
    }

private:
    void create() {
        if (!eglBindAPI(EGL_OPENGL_API)) throw Error(eglFailure("eglBindAPI(EGL_OPENGL_API)"));
        const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                                        EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24,
                                        EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint found = 0;
        if (!eglChooseConfig(display_, configAttribs, &config, 1, &found) || found < 1)
            throw Error("no EGL config with an RGBA8 + depth 24 pbuffer for desktop OpenGL");
        const EGLint pbufferAttribs[] = {EGL_WIDTH, width_, EGL_HEIGHT, height_, EGL_NONE};
        surface_ = eglCreatePbufferSurface(display_, config, pbufferAttribs);
        if (surface_ == EGL_NO_SURFACE)
            throw Error(str(eglFailure("eglCreatePbufferSurface"), " (", width_, "x", height_, ")"));
        const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
        if (context_ == EGL_NO_CONTEXT) throw Error(eglFailure("creating an OpenGL 4.5 core context"));
        makeCurrent();
    }
    void destroy() {
        if (eglGetCurrentContext() == context_ && context_ != EGL_NO_CONTEXT)
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
        if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
        releaseDisplay(display_);
    }

    int width_, height_;
    EGLDisplay display_;
    std::string label_;
    EGLSurface surface_ = EGL_NO_SURFACE;
    EGLContext context_ = EGL_NO_CONTEXT;
};

} // namespace

namespace detail {

std::unique_ptr<GlContext> createEglContext(const GlContextConfig& config, GlBackend which) {
    if (config.width <= 0 || config.height <= 0)
        throw Error(str("headless context size must be positive, got ", config.width, "x", config.height));
    const EglEntryPoints egl = entryPoints();
    std::string why;
    std::vector<Candidate> candidates;
    auto add = [&](std::vector<Candidate> more) { candidates.insert(candidates.end(), more.begin(), more.end()); };
    if (which == GlBackend::Egl || which == GlBackend::EglDevice) add(deviceCandidates(egl, false, why));
    if (which == GlBackend::Egl || which == GlBackend::EglSurfaceless) add(surfacelessCandidate(egl, why));
    if (which == GlBackend::Egl || which == GlBackend::EglDevice) add(deviceCandidates(egl, true, why));
    for (const Candidate& c : candidates) {
        try {
            acquireDisplay(c.display);
        } catch (const Error& e) {
            why += str("; ", c.label, ": ", e.what());
            continue;
        }
        try {
            return std::make_unique<EglContext>(config, c.display, c.label);
        } catch (const Error& e) {
            why += str("; ", c.label, ": ", e.what());
        }
    }
    throw Error(str("no ", glBackendName(which), " context with OpenGL 4.5 core",
                    why.empty() ? std::string() : ": " + why.substr(2),
                    " (on Debian: apt-get install libegl1 libegl-mesa0)"));
}

} // namespace detail

} // namespace hfx
