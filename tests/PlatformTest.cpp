// Where GL contexts come from (platform/): every off-screen backend this machine has renders the
// module's frames as OSMesa does, the backends are chosen and refused by name, and the process can
// move between contexts of different backends (their entry points differ).

#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/tools/AccuracyMaps.h"
#include "hfx/tools/AccuracyProbe.h"

#include <cmath>
#include <cstdlib>

namespace hfx::test {
namespace {

constexpr int kField = 64;
constexpr int kImage = 192;

/// The exact tracer's frame of a smooth relief at 60 degrees with soft shadows, drawn by the
/// module in a fresh context of `backend`: uploads, the pyramid, the beam start and the draw.
Image frameFrom(ClContext& cl, GlBackend backend, std::string* label) {
    auto gl = createHeadlessContext({.width = 64, .height = 64, .backend = backend});
    *label = gl->description();
    Image frame;
    {
        AccuracyProbe probe(cl, smoothWaves(kField), kField, 0.1f);
        probe.timeDraw(Technique::Hierarchical,
                       {.angleDegrees = 60.0, .shadows = true, .light = accuracyLight()}, kImage,
                       kImage, 1);
        frame = probe.lastFrame();
    } // the probe's GL objects go with its context, before it
    return frame;
}

class Platform : public DeviceTest {};

// The bound: every EGL mode renders OSMesa's image within 1/255 on llvmpipe (both are
// Mesa's llvmpipe, so the same rasteriser draws the same pixels; 1/255 allows an 8-bit rounding).
TEST_F(Platform, EveryEglModeRendersTheFrameOsMesaRenders) {
    std::string osmesaLabel;
    Image reference;
    try {
        reference = frameFrom(cl(), GlBackend::OsMesa, &osmesaLabel);
    } catch (const Error& e) {
        GTEST_SKIP() << "no OSMesa here: " << e.what();
    }
    ASSERT_NE(osmesaLabel.find("OSMesa"), std::string::npos) << osmesaLabel;
    int modes = 0;
    for (GlBackend backend : {GlBackend::EglDevice, GlBackend::EglSurfaceless}) {
        std::string label;
        Image frame;
        try {
            frame = frameFrom(cl(), backend, &label);
        } catch (const Error& e) {
            std::printf("%s: not available here (%s)\n", glBackendName(backend), e.what());
            continue;
        }
        ++modes;
        std::printf("%s\n", label.c_str());
        EXPECT_NE(label.find("EGL"), std::string::npos) << label;
        ASSERT_EQ(frame.pixels.size(), reference.pixels.size());
        double worst = 0.0, lit = 0.0;
        for (size_t i = 0; i < frame.pixels.size(); ++i) {
            worst = std::max(worst, double(std::abs(frame.pixels[i] - reference.pixels[i])));
            lit += frame.pixels[i];
        }
        EXPECT_LE(worst, 1.0 / 255.0 + 1e-6) << glBackendName(backend) << " against " << osmesaLabel;
        // A frame of the relief, not a cleared target: the comparison could fail.
        EXPECT_GT(lit / double(frame.pixels.size()), 0.05) << glBackendName(backend);
        if (worst > 1.0 / 255.0) {
            writeImage(outputPath(str("platform_", glBackendName(backend), ".png")), frame);
            writeImage(outputPath("platform_osmesa.png"), reference);
        }
    }
    // This machine has Mesa's EGL with both platforms (CI's too): neither missing goes unnoticed.
    if (std::getenv("HFX_REQUIRE_EGL")) {
        EXPECT_EQ(modes, 2);
    }
}

TEST_F(Platform, BackendsAreNamedParsedAndRefusedByName) {
    for (GlBackend b : {GlBackend::Auto, GlBackend::Egl, GlBackend::EglDevice, GlBackend::EglSurfaceless,
                        GlBackend::OsMesa})
        EXPECT_EQ(parseGlBackend(glBackendName(b)), b);
    const std::string m = messageOf([] { parseGlBackend("vulkan"); });
    EXPECT_NE(m.find("vulkan"), std::string::npos) << m;
    EXPECT_NE(m.find("egl-surfaceless"), std::string::npos) << m; // lists what is known
    EXPECT_NE(messageOf([] { createHeadlessContext({.width = 0, .height = 16, .backend = GlBackend::EglSurfaceless}); })
                  .find("0x16"),
              std::string::npos);
}

TEST_F(Platform, HfxGlChoosesTheBackendAndAnUnknownOneIsRefused) {
    const char* saved = std::getenv("HFX_GL");
    const std::string before = saved ? saved : "";
    setenv("HFX_GL", "osmesa", 1);
    EXPECT_EQ(resolveGlBackend(GlBackend::Auto), GlBackend::OsMesa);
    EXPECT_EQ(resolveGlBackend(GlBackend::EglDevice), GlBackend::EglDevice); // an explicit choice wins
    setenv("HFX_GL", "glide", 1);
    const std::string m = messageOf([] { resolveGlBackend(GlBackend::Auto); });
    EXPECT_NE(m.find("HFX_GL"), std::string::npos) << m;
    EXPECT_NE(m.find("glide"), std::string::npos) << m;
    if (saved) {
        setenv("HFX_GL", before.c_str(), 1);
    } else {
        unsetenv("HFX_GL");
    }
    EXPECT_EQ(resolveGlBackend(GlBackend::Auto), saved ? parseGlBackend(before) : GlBackend::Auto);
}

// The shared context comes back whole after another backend's context came and went: its entry
// points are reloaded when it is made current again.
TEST_F(Platform, TheSharedContextDrawsAgainAfterAnotherBackendsContext) {
    const GlRendererInfo before = currentGlRenderer();
    {
        std::unique_ptr<GlContext> other;
        try {
            other = createHeadlessContext({.width = 16, .height = 16, .backend = GlBackend::OsMesa});
        } catch (const Error& e) {
            GTEST_SKIP() << "no OSMesa here: " << e.what(); // a GPU machine without Mesa
        }
        GLuint texture = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        EXPECT_NE(texture, 0u);
        glDeleteTextures(1, &texture);
    }
    DeviceTest::SetUp(); // what the next test's fixture does: the shared context made current again
    EXPECT_EQ(currentGlRenderer().renderer, before.renderer);
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    EXPECT_NE(texture, 0u);
    glTextureStorage2D(texture, 1, GL_RGBA8, 4, 4);
    GLint width = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &width);
    EXPECT_EQ(width, 4);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    glDeleteTextures(1, &texture);
}

} // namespace
} // namespace hfx::test
