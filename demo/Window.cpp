#include "Window.h"

#include "Frames.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/RenderTarget.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace hfx::demo {
namespace {

double nowMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Owns the ImGui context and its GLFW and OpenGL back-ends for the loop's lifetime.
class ImGuiSession {
public:
    explicit ImGuiSession(GLFWwindow* window) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr; // no imgui.ini left in the working directory
        if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 450")) {
            ImGui::DestroyContext();
            throw Error("Dear ImGui could not initialise its GLFW/OpenGL back-ends");
        }
    }
    ~ImGuiSession() {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    ImGuiSession(const ImGuiSession&) = delete;
    ImGuiSession& operator=(const ImGuiSession&) = delete;
};

/// True once per press.
class KeyEdge {
public:
    explicit KeyEdge(int key) : key_(key) {}
    bool pressed(GLFWwindow* w) {
        const bool down = glfwGetKey(w, key_) == GLFW_PRESS;
        const bool edge = down && !was_;
        was_ = down;
        return edge;
    }

private:
    int key_;
    bool was_ = false;
};

/// The default framebuffer's back buffer as the user will see it after the swap.
void saveWindow(const std::string& path, glm::ivec2 size) {
    std::vector<unsigned char> rgba(size_t(size.x) * size.y * 4);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    Image image{size.x, size.y, 3, std::vector<float>(size_t(size.x) * size.y * 3)};
    for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x)
            for (int c = 0; c < 3; ++c)
                image.at(x, size.y - 1 - y, c) = rgba[(size_t(y) * size.x + x) * 4 + c] / 255.0f;
    writeImage(path, image);
    std::printf("wrote %s (the window)\n", path.c_str());
}

} // namespace

int WindowLoop::run(GlContext& gl, Scene& scene) {
    GLFWwindow* window = glfwGetCurrentContext();
    if (gl.headless() || !window) throw Error("WindowLoop needs a GLFW window context");
    ImGuiSession imgui(window);
    RenderTarget target(options_.width, options_.height);
    CameraOrbit orbit(scene.camera());
    KeyEdge explodeKey(GLFW_KEY_E), clearKey(GLFW_KEY_C), screenshotKey(GLFW_KEY_F12), escapeKey(GLFW_KEY_ESCAPE);
    if (!options_.out.empty()) makeFolder(options_.out, "--out");
    int screenshots = 0;
    double drawMs = 0.0, frameMs = 0.0, last = nowMs();
    double pathSeconds = 0.0; // how far along its --camera-path the camera is
    // The techniques this scene can draw: those that walk the height bounds only on one grid
    // that can carry them (not the ocean's cascades; power-of-two sizes, a float format).
    std::vector<Technique> offered;
    const bool boundable = scene.effect().layers().size() == 1 &&
                           carriesBounds(scene.effect().textures().config());
    for (const TechniqueInfo& t : kTechniqueTable)
        if (!t.needsPyramid || boundable) offered.push_back(t.technique);
    int techniqueIndex = 0;
    for (int i = 0; i < int(offered.size()); ++i)
        if (offered[i] == scene.technique) techniqueIndex = i;

    for (int frame = 0; options_.frames == 0 || frame < options_.frames; ++frame) {
        if (!gl.pollEvents() || escapeKey.pressed(window)) break;
        const double now = nowMs();
        const double dt = frame == 0 ? 0.0 : std::clamp((now - last) / 1000.0, 1e-4, 0.25);
        frameMs = now - last;
        last = now;

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ImGuiIO& io = ImGui::GetIO();

        // Mouse: right-drag orbits, the wheel zooms, a left click (not a drag) shoots.
        const auto toImage = [&](ImVec2 p) {
            return ImVec2(p.x / std::max(io.DisplaySize.x, 1.0f) * options_.width,
                          p.y / std::max(io.DisplaySize.y, 1.0f) * options_.height);
        };
        if (!io.WantCaptureMouse) {
            if (ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
                orbit.azimuth -= io.MouseDelta.x * 0.008f;
                orbit.elevation = std::clamp(orbit.elevation + io.MouseDelta.y * 0.008f, -1.5f, 1.5f);
            }
            if (io.MouseWheel != 0.0f) orbit.distance = std::clamp(orbit.distance * std::pow(0.9f, io.MouseWheel), 0.3f, 80.0f);
            if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && io.MouseDragMaxDistanceSqr[0] < io.MouseDragThreshold * io.MouseDragThreshold) {
                const ImVec2 p = toImage(io.MousePos);
                scene.click(p.x, p.y, options_.width, options_.height);
            }
        }
        orbit.apply(scene.camera());
        if (scene.cameraTurn != 0.0f) { // --camera-turn, as the headless frames turn it
            scene.turnCamera(scene.cameraTurn * float(dt));
            orbit = CameraOrbit(scene.camera());
        }
        if (scene.cameraPath && pathSeconds <= scene.cameraPath->duration()) {
            // --camera-path, on the window's clock, once: its last key's placement, then the mouse's.
            pathSeconds += dt;
            scene.followPath(std::min(pathSeconds, scene.cameraPath->duration()));
            orbit = CameraOrbit(scene.camera());
        }
        if (!io.WantCaptureKeyboard) {
            if (explodeKey.pressed(window)) {
                const ImVec2 p = toImage(io.MousePos);
                scene.explode(p.x, p.y, options_.width, options_.height);
            }
            if (clearKey.pressed(window)) scene.clear();
        }
        const bool screenshot = screenshotKey.pressed(window);

        // The panel: every parameter of the draw, the scene's own, and the frame's breakdown.
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
        ImGui::Begin("HFX");
        ImGui::Text("%s scene", scene.name());
        // The effect owns the material: edit a copy, hand it back when it changed.
        SurfaceMaterial m = scene.effect().material();
        const SurfaceMaterial before = m;
        if (ImGui::Combo("technique", &techniqueIndex, [](void* list, int i, const char** out) {
                *out = techniqueName((*static_cast<const std::vector<Technique>*>(list))[i]);
                return true;
            }, &offered, int(offered.size())))
            scene.technique = offered[techniqueIndex];
        ImGui::SliderInt("samples min", &m.minSamples, 1, 128);
        ImGui::SliderInt("samples max", &m.maxSamples, 1, 256);
        m.maxSamples = std::max(m.maxSamples, m.minSamples);
        ImGui::SliderFloat("depth scale", &m.depthScale, 0.001f, 0.3f, "%.4f", ImGuiSliderFlags_Logarithmic);
        ImGui::Checkbox("soft shadows", &m.shadows);
        ImGui::SliderInt("shadow samples", &m.shadowSamples, 1, 32);
        ImGui::Checkbox("bounded search", &m.boundedSearch);
        ImGui::SliderFloat("LOD threshold", &m.lodThreshold, 0.0f, 12.0f);
        ImGui::Checkbox("wireframe of the base mesh", &scene.wireframe);
        if (!(before == m)) scene.effect().setMaterial(m);
        scene.panel(); // after: the scene's controls may change the material too (the wind, the sea's depth)
        const StageTimes stages = scene.effect().lastTimes();
        ImGui::Separator();
        ImGui::Text("compute not hidden by the draw %.2f ms  upload %.2f ms", stages.compute, stages.upload);
        ImGui::Text("draw %.2f ms  frame %.1f ms (%.1f fps)", drawMs, frameMs, frameMs > 0 ? 1000.0 / frameMs : 0.0);
        if (scene.pixelsPerTexel() > 0.0)
            ImGui::Text("texel shadows %s (%.2f pixels per texel)", scene.texelShadowsLabel().c_str(),
                        scene.pixelsPerTexel());
        ImGui::Text("right-drag orbit, wheel zoom, F12 screenshot");
        ImGui::End();

        // Overlapped: the field started after the last frame's draw is taken to GL now, and the
        // next one starts once this frame's draw is issued.
        if (frame > 0) scene.endUpdate();
        target.bind();
        const double drawStart = nowMs();
        scene.drawInto(target, options_.background);
        scene.beginUpdate(std::max(dt, 1e-4));
        glFinish();
        drawMs = nowMs() - drawStart; // the draw, with the next field's compute beside it

        const bool saveFrame = !options_.out.empty() && options_.frames > 0;
        if (screenshot || saveFrame) {
            const std::string dir = options_.out.empty() ? "." : options_.out;
            const std::string path = screenshot ? framePath(dir, std::string(scene.name()) + "_shot", screenshots++)
                                                : framePath(dir, scene.name(), frame);
            writeImage(path, target.readColor());
            std::printf("wrote %s\n", path.c_str());
        }

        const glm::ivec2 size = gl.framebufferSize();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBlitNamedFramebuffer(target.framebuffer(), 0, 0, 0, options_.width, options_.height, 0, 0, size.x, size.y,
                               GL_COLOR_BUFFER_BIT, GL_LINEAR);
        glViewport(0, 0, size.x, size.y);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (!options_.windowShot.empty() && frame + 1 == options_.frames) saveWindow(options_.windowShot, size);
        gl.swapBuffers();
    }
    if (!options_.exportMaps.empty()) exportMaps(options_.exportMaps, scene.effect().textures());
    scene.finish();
    return 0;
}

} // namespace hfx::demo
