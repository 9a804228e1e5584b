#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/effects/tracer/BoundsPass.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace hfx::test {
namespace {
// The shared contexts are never destroyed: at exit, static destructors would release OpenCL
// objects after PoCL's own teardown may have begun (seen as a rare crash after all tests
// passed). The process's end releases them.
ClContext* sharedCl = nullptr;
std::string clError;
bool clTried = false;
GlContext* sharedGl = nullptr;
std::string glError;
bool glTried = false;

ClContext* acquireCl() {
    if (!clTried) {
        clTried = true;
        try {
            sharedCl = new ClContext();
        } catch (const Error& e) {
            clError = e.what();
        }
    }
    return sharedCl;
}

GlContext* acquireGl() {
    if (!glTried) {
        glTried = true;
        try {
            sharedGl = createHeadlessContext({.width = 64, .height = 64}).release();
            std::fprintf(stderr, "hfx tests: GL %s\n", sharedGl->description().c_str());
            // llvmpipe rasterises on its own threads behind the caller. Mesa's exit handler,
            // registered before this one and so run after it, stops them and joins them; with a
            // scene still in flight one thread can be left at the scene's barrier and the join
            // hangs for ever (seen once in CI: a test that had passed, stuck in exit). Let the
            // rasteriser finish first.
            std::atexit([] { glFinish(); });
        } catch (const Error& e) {
            glError = e.what();
        }
    }
    return sharedGl;
}
} // namespace


std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

void ClTest::SetUp() {
    if (!acquireCl()) GTEST_SKIP() << "no OpenCL device: " << clError;
}

ClContext& ClTest::cl() { return *acquireCl(); }

namespace {
// PoCL compiles kernels on its own threads at first launch; a process that exits while one is
// compiling aborts in LLVM's teardown. Every device test waits for its work before it ends.
void drain() {
    if (sharedCl) sharedCl->queue().finish();
}
} // namespace

/// No test leaves a GL error behind: a call whose error nobody checked would otherwise be blamed
/// on the next checked call, in whichever test makes it.
void expectNoGlError() {
    if (!sharedGl) return;
    sharedGl->makeCurrent();
    for (GLenum e = glGetError(), n = 0; e != GL_NO_ERROR && n < 8; e = glGetError(), ++n)
        ADD_FAILURE() << "the test left GL error 0x" << std::hex << e << " unchecked";
}

void ClTest::TearDown() { drain(); }
void DeviceTest::TearDown() {
    drain();
    expectNoGlError();
}
void GlTest::TearDown() { expectNoGlError(); }
ClContext& DeviceTest::cl() { return *acquireCl(); }

void GlTest::SetUp() {
    if (!acquireGl()) GTEST_SKIP() << "no OpenGL 4.5 context: " << glError;
    sharedGl->makeCurrent();
}

void DeviceTest::SetUp() {
    if (!acquireGl()) GTEST_SKIP() << "no OpenGL 4.5 context: " << glError;
    if (!acquireCl()) GTEST_SKIP() << "no OpenCL device: " << clError;
    sharedGl->makeCurrent();
}

std::string outputPath(const std::string& fileName) {
    const char* env = std::getenv("HFX_TEST_OUTPUT_DIR");
    const std::filesystem::path dir = env && *env ? env : HFX_TEST_OUTPUT_DIR;
    std::filesystem::create_directories(dir);
    return (dir / fileName).string();
}

std::string shaderSourceDir() {
    const char* env = std::getenv("HFX_SHADER_SOURCE_DIR");
    return env && *env ? env : HFX_SHADER_SOURCE_DIR;
}

PatchedShaders::PatchedShaders(const std::string& name, const std::string& from, const std::string& to,
                               const std::string& file) {
    const std::filesystem::path dir = outputPath(name);
    std::filesystem::remove_all(dir);
    std::filesystem::copy(shaderSourceDir(), dir, std::filesystem::copy_options::recursive);
    std::stringstream source;
    source << std::ifstream(dir / file).rdbuf();
    std::string text = source.str();
    if (text.find(from) == std::string::npos) throw Error(str(file, " has no '", from, "' to patch"));
    text.replace(text.find(from), from.size(), to);
    std::ofstream(dir / file) << text;
    if (const char* callers = std::getenv("HFX_SHADER_DIR")) callers_ = callers;
    setenv("HFX_SHADER_DIR", dir.c_str(), 1);
}

PatchedShaders::~PatchedShaders() {
    if (callers_) setenv("HFX_SHADER_DIR", callers_->c_str(), 1);
    else unsetenv("HFX_SHADER_DIR");
}

std::vector<float> readBoundsLevel(const HeightBounds& bounds, int level) {
    const int w = std::max(bounds.width() >> level, 1), h = std::max(bounds.height() >> level, 1);
    std::vector<float> stored(2 * size_t(w) * size_t(h));
    const GLsizei bytes = GLsizei(stored.size() * sizeof(float));
    if (bounds.layout() == PyramidLayout::MipChain) {
        glGetTextureImage(bounds.pyramid(), level, GL_RG, GL_FLOAT, bytes, stored.data());
    } else {
        const auto [x, y] = HeightBounds::atlasOrigin(bounds.width(), bounds.height(), level);
        glGetTextureSubImage(bounds.pyramid(), 0, x, y, 0, w, h, 1, GL_RG, GL_FLOAT, bytes, stored.data());
    }
    return stored;
}

std::vector<float> readPyramidLevel(const SurfaceTextures& textures, int level, PyramidLayout layout) {
    HeightBounds bounds(textures.config(), layout);
    BoundsPass().refresh(textures, bounds, false); // what a draw would read: built from the current texels
    return readBoundsLevel(bounds, level);
}

std::vector<float> readSurface(const SurfaceTextures& textures) {
    std::vector<float> texels(size_t(textures.config().width) * textures.config().height * 4);
    glGetTextureImage(textures.surface(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
    return texels;
}

std::vector<float> readFloats(ClContext& cl, const cl::Buffer& buffer, size_t count) {
    std::vector<float> out(count);
    cl.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), out.data());
    return out;
}

std::vector<float> readHeights(ClContext& cl, const HeightSource& source) {
    return readFloats(cl, source.buffer(), size_t(source.width()) * source.height());
}

} // namespace hfx::test
