#pragma once
// What the compute side may know of the caller's GL context: who renders it (to put the compute
// device on the same hardware) and, for cl_khr_gl_sharing, its native handles. Plain data, so
// that compute never asks GL for it behind the caller's back.
//
// Thread: currentGlRenderer() on the thread whose context is current; the rest any.

#include <string>

namespace hfx {

/// glGetString(GL_VENDOR) and glGetString(GL_RENDERER); empty when not known.
struct GlRendererInfo {
    std::string vendor;
    std::string renderer;
    bool empty() const { return vendor.empty() && renderer.empty(); }
    /// A CPU rasteriser (llvmpipe, softpipe, swrast, SwiftShader, Microsoft's basic renderer).
    bool software() const;
};

/// The renderer of the current context.
GlRendererInfo currentGlRenderer();

/// A GL context's native handles, as cl_khr_gl_sharing takes them (CL_GL_CONTEXT_KHR with
/// CL_GLX_DISPLAY_KHR or CL_EGL_DISPLAY_KHR). None: the context cannot be shared (OSMesa).
struct GlShareHandles {
    enum class Api { None, Glx, Egl };
    Api api = Api::None;
    void* context = nullptr; ///< GLXContext or EGLContext
    void* display = nullptr; ///< X11 Display* or EGLDisplay
};

} // namespace hfx
