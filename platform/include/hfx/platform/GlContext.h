#pragma once
// One interface over the places a GL 4.5 core context can come from: a GLFW window, or off
// screen through EGL (a GPU's EGL device, Mesa's surfaceless platform, Mesa's software device)
// or OSMesa (Mesa's llvmpipe linked into the process; no display, no GPU). Only the demo and
// tests create contexts; the module's renderers draw into whatever context and framebuffer the
// caller has current.
//
// Which off-screen backend: GlContextConfig::backend, else the HFX_GL environment variable
// (auto, egl, egl-device, egl-surfaceless, osmesa), else auto: EGL, else OSMesa. Within EGL a
// hardware device comes first, then the surfaceless platform, then Mesa's software device.
//
// Thread: a context is current on the thread that created it; use it from that thread only.

#include "hfx/core/GlLoader.h"
#include "hfx/core/GlRenderer.h"

#include <glm/vec2.hpp>

#include <memory>
#include <string>
#include <string_view>

namespace hfx {

enum class GlBackend {
    Auto,           ///< HFX_GL when set, else EGL (any platform), else OSMesa
    Egl,            ///< EGL: a hardware device, else the surfaceless platform, else a software device
    EglDevice,      ///< EGL_EXT_platform_device only (a GPU, else Mesa's software device)
    EglSurfaceless, ///< EGL_MESA_platform_surfaceless only (Mesa's drivers, llvmpipe without one)
    OsMesa,         ///< OSMesa: Mesa's llvmpipe in the process, the CPU path
};
/// "auto", "egl", "egl-device", "egl-surfaceless", "osmesa".
const char* glBackendName(GlBackend backend);
/// The inverse of glBackendName; throws hfx::Error naming the known backends.
GlBackend parseGlBackend(std::string_view name);
/// "auto, egl, egl-device, egl-surfaceless, osmesa", for help texts.
std::string glBackendNames();
/// `requested` unless it is Auto, then HFX_GL's backend when set (Auto when not); throws
/// hfx::Error for an HFX_GL it does not know.
GlBackend resolveGlBackend(GlBackend requested);

class GlContext {
public:
    virtual ~GlContext() = default;
    /// Makes the context current on this thread, and loads its GL entry points when the process
    /// last loaded another backend's (OSMesa's differ from EGL's).
    virtual void makeCurrent() = 0;
    /// Presents the default framebuffer (a no-op off screen).
    virtual void swapBuffers() = 0;
    /// Processes window events; false once the user asked to close (always true off screen).
    virtual bool pollEvents() = 0;
    virtual glm::ivec2 framebufferSize() const = 0;
    virtual bool headless() const = 0;
    /// Where the context came from: "EGL device 'NVIDIA' (EGL_NV_device_cuda)", "EGL surfaceless",
    /// "EGL device (Mesa software)", "OSMesa", "GLFW window".
    virtual std::string backend() const = 0;
    /// The native handles an OpenCL context can share this context through (cl_khr_gl_sharing:
    /// ClContextConfig::glShare); None for OSMesa.
    virtual GlShareHandles shareHandles() const { return {}; }
    /// "EGL surfaceless: OpenGL 4.5 (Core Profile) Mesa ..., llvmpipe (...)", for logs.
    std::string description() const;
};

struct GlContextConfig {
    int width = 1280;
    int height = 720;
    std::string title = "HFX";
    bool visible = true;   ///< window only: false keeps it hidden (tests)
    bool vsync = false;    ///< window only
    GlBackend backend = GlBackend::Auto; ///< off screen: see the top of this file
};

/// An off-screen OpenGL 4.5 core context from config.backend (see the top of this file). Its
/// default framebuffer is width x height RGBA8 with a 24-bit depth buffer; render into your own
/// framebuffer objects for other formats. Throws hfx::Error with every backend's reason when
/// none gives a context.
std::unique_ptr<GlContext> createHeadlessContext(const GlContextConfig& config = {});
/// A GLFW window with an OpenGL 4.5 core context. Throws hfx::Error when no display exists.
std::unique_ptr<GlContext> createWindowContext(const GlContextConfig& config = {});
/// A window when a display is reachable, preferWindow is set and the backend is Auto (after
/// HFX_GL), else headless.
std::unique_ptr<GlContext> createContext(const GlContextConfig& config, bool preferWindow);

namespace detail {
/// Whether the process-wide entry points are `loader`'s now. When they are another backend's,
/// that backend's context may have replaced this one in Mesa's shared dispatch without the
/// window system knowing: makeCurrent() then releases its context first, so that making it
/// current again is not skipped as a no-op.
bool glEntryPointsFrom(GlProcLoader loader);
/// Loads the entry points through `loader` unless they are its already: called by every
/// backend's makeCurrent().
void bindGlEntryPoints(GlProcLoader loader);
/// The backends behind createHeadlessContext; each throws hfx::Error saying why it has none.
std::unique_ptr<GlContext> createEglContext(const GlContextConfig& config, GlBackend which);
std::unique_ptr<GlContext> createOsMesaContext(const GlContextConfig& config);
} // namespace detail

} // namespace hfx
