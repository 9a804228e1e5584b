// Only OSMesa's header here: it includes the system GL/gl.h, which must not meet glad's.
#include <GL/osmesa.h>

#include "hfx/core/Error.h"
#include "hfx/platform/GlContext.h"
#include "hfx/core/GlLoader.h"

#include <vector>

namespace hfx {
namespace {

GlProc osmesaProc(const char* name) { return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name)); }

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(const GlContextConfig& config)
        : width_(config.width), height_(config.height) {
        if (width_ <= 0 || height_ <= 0)
            throw Error(str("headless context size must be positive, got ", width_, "x", height_));
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
        context_ = OSMesaCreateContextAttribs(attribs, nullptr);
        if (!context_)
            throw Error("OSMesa could not create an OpenGL 4.5 core context (needs Mesa's "
                        "llvmpipe: apt-get install libosmesa6)");
        pixels_.resize(static_cast<size_t>(width_) * height_);
        try {
            makeCurrent();
        } catch (...) {
            OSMesaDestroyContext(context_);
            throw;
        }
    }
    ~OsMesaContext() override {
        // llvmpipe rasterises behind the caller: let it finish before the context goes (Mesa's
        // exit handler can hang joining a rasteriser thread left inside a scene).
        if (OSMesaGetCurrentContext() == context_) glFinish();
        OSMesaDestroyContext(context_);
    }

    void makeCurrent() override {
        if (!OSMesaMakeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, width_, height_))
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
