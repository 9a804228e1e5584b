#pragma once
// One interface over the places a GL 4.5 core context can come from: an off-screen OSMesa
// context (no display, no GPU) or a GLFW window. Only the demo and tests create contexts; the
// module's renderers draw into whatever context and framebuffer the caller has current.
//
// Thread: a context is current on the thread that created it; use it from that thread only.

#include <glm/vec2.hpp>

#include <memory>
#include <string>

namespace hfx {

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual void makeCurrent() = 0;
    /// Presents the default framebuffer (a no-op off screen).
    virtual void swapBuffers() = 0;
    /// Processes window events; false once the user asked to close (always true off screen).
    virtual bool pollEvents() = 0;
    virtual glm::ivec2 framebufferSize() const = 0;
    virtual bool headless() const = 0;
    /// "OpenGL 4.5 (Core Profile) Mesa ..., llvmpipe (...)", for logs.
    std::string description() const;
};

struct GlContextConfig {
    int width = 1280;
    int height = 720;
    std::string title = "HFX";
    bool visible = true;   ///< window only: false keeps it hidden (tests)
    bool vsync = false;    ///< window only
};

/// Off-screen OpenGL 4.5 core context through OSMesa. Its default framebuffer is
/// width x height RGBA8; render into your own framebuffer objects for other formats.
std::unique_ptr<GlContext> createHeadlessContext(const GlContextConfig& config = {});
/// A GLFW window with an OpenGL 4.5 core context. Throws hfx::Error when no display exists.
std::unique_ptr<GlContext> createWindowContext(const GlContextConfig& config = {});
/// A window when a display is reachable and preferWindow is set, else headless.
std::unique_ptr<GlContext> createContext(const GlContextConfig& config, bool preferWindow);

} // namespace hfx
