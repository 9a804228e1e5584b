#pragma once
// The interactive loop: mouse orbit and zoom, clicks and keys handed to the scene, a Dear ImGui
// panel for every parameter, an on-screen frame-time breakdown and a screenshot key.

#include "Scene.h"

#include "hfx/platform/GlContext.h"

#include <glm/vec4.hpp>

#include <string>

namespace hfx::demo {

struct WindowOptions {
    int width = 1280, height = 720; ///< the rendered image (scaled to the window)
    int frames = 0;                 ///< close after this many frames (0: when the user closes)
    std::string out;                ///< screenshots and, with frames, every frame go here
    std::string exportMaps;         ///< on close, export the field's maps here
    std::string windowShot;         ///< with frames: save the last frame as the window shows it (panel too)
    glm::vec4 background{0, 0, 0, 1};
};

class WindowLoop {
public:
    explicit WindowLoop(const WindowOptions& options) : options_(options) {}
    /// Runs until the window closes or `frames` have been drawn; the context must be a window.
    int run(GlContext& gl, Scene& scene);

private:
    WindowOptions options_;
};

} // namespace hfx::demo
