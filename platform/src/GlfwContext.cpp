#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/platform/GlContext.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#define GLFW_EXPOSE_NATIVE_GLX
#include <GLFW/glfw3native.h>

#include <mutex>

namespace hfx {
namespace {

std::string lastGlfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown GLFW error";
}

class GlfwContext final : public GlContext {
public:
    explicit GlfwContext(const GlContextConfig& config) {
        if (!glfwInit()) throw Error("GLFW could not initialise: " + lastGlfwError());
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_VISIBLE, config.visible ? GLFW_TRUE : GLFW_FALSE);
        window_ = glfwCreateWindow(config.width, config.height, config.title.c_str(), nullptr,
                                   nullptr);
        if (!window_) {
            const std::string why = lastGlfwError();
            glfwTerminate();
            throw Error("GLFW could not open a window with OpenGL 4.5 core: " + why);
        }
        glfwMakeContextCurrent(window_);
        glfwSwapInterval(config.vsync ? 1 : 0);
        try {
            makeCurrent();
        } catch (...) {
            glfwDestroyWindow(window_);
            glfwTerminate();
            throw;
        }
    }
    ~GlfwContext() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }

    void makeCurrent() override {
        const auto loader = reinterpret_cast<GlProcLoader>(&glfwGetProcAddress);
        if (!detail::glEntryPointsFrom(loader)) glfwMakeContextCurrent(nullptr);
        glfwMakeContextCurrent(window_);
        detail::bindGlEntryPoints(loader);
    }
    void swapBuffers() override { glfwSwapBuffers(window_); }
    bool pollEvents() override {
        glfwPollEvents();
        return !glfwWindowShouldClose(window_);
    }
    glm::ivec2 framebufferSize() const override {
        glm::ivec2 size;
        glfwGetFramebufferSize(window_, &size.x, &size.y);
        return size;
    }
    bool headless() const override { return false; }
    std::string backend() const override { return "GLFW window"; }
    GlShareHandles shareHandles() const override {
        // Only a GLX window (X11) has handles cl_khr_gl_sharing takes; elsewhere none.
        GLXContext context = glfwGetGLXContext(window_);
        Display* display = glfwGetX11Display();
        if (!context || !display) {
            glfwGetError(nullptr); // the query's "not an X11 window" is not an error of ours
            return {};
        }
        return {.api = GlShareHandles::Api::Glx, .context = context, .display = display};
    }

private:
    GLFWwindow* window_ = nullptr;
};

} // namespace

std::unique_ptr<GlContext> createWindowContext(const GlContextConfig& config) {
    return std::make_unique<GlfwContext>(config);
}

} // namespace hfx
