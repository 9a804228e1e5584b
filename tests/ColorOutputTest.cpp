// The colours the draws write (hfx::ColorOutput): display values (clamped, gamma 2.2) into a
// plain 8-bit target; linear radiance, unclamped, into an engine's float target or an sRGB one
// that GL encodes. The same frame either way: the linear one encodes to the display one.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/core/Gl.h"
#include "hfx/core/GlObject.h"
#include "hfx/effects/OceanEffect.h"
#include "hfx/effects/PlanetRings.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

namespace hfx::test {
namespace {

class ColorOutputTest : public DeviceTest {};

constexpr int W = 200, H = 120;

/// A framebuffer of one colour format (and a float depth) at W x H.
struct Target {
    explicit Target(GLenum f)
        : format(f), color(GlTexture::create()), depth(GlTexture::create()), fbo(GlFramebuffer::create()) {
        glTextureStorage2D(color.id(), 1, format, W, H);
        glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, W, H);
        glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
        glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
        EXPECT_EQ(glCheckNamedFramebufferStatus(fbo.id(), GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    }
    void bind() const {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, W, H);
        const float black[4] = {0, 0, 0, 1}, far = 1.0f;
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, black);
        glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
    }
    /// RGB as stored: an 8-bit format's bytes / 255 (an sRGB one's encoded), a float one's values.
    std::vector<glm::vec3> read() const {
        std::vector<glm::vec3> rgb(size_t(W) * H);
        if (format == GL_RGBA16F) {
            std::vector<float> texels(size_t(W) * H * 4);
            glGetTextureImage(color.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
            for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = {texels[4 * i], texels[4 * i + 1], texels[4 * i + 2]};
        } else {
            std::vector<unsigned char> bytes(size_t(W) * H * 4);
            glGetTextureImage(color.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(bytes.size()), bytes.data());
            for (size_t i = 0; i < rgb.size(); ++i)
                rgb[i] = glm::vec3(bytes[4 * i], bytes[4 * i + 1], bytes[4 * i + 2]) / 255.0f;
        }
        return rgb;
    }
    GLenum format;
    GlTexture color, depth;
    GlFramebuffer fbo;
};

float srgbDecode(float e) { return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f); }

/// A sea under a low sun seen against it (its glint far above 1 in linear light), its sky behind,
/// and a planet's rings over both, into the bound target.
struct SunlitSea {
    explicit SunlitSea(ClContext& cl) : ocean(cl, {.ocean = {.size = 64, .cascades = 1}}) {
        camera.position = {0.0f, 2.0f, 6.0f};
        camera.target = {0.0f, 0.0f, -4.0f};
        camera.aspect = float(W) / float(H);
    }
    void draw(const Target& target) {
        target.bind();
        renderer.drawSky(camera, light, ocean.material().water);
        const std::vector<SurfaceLayer> layers = ocean.layers();
        renderer.draw(plane, glm::mat4(1.0f), layers, ocean.material(), camera, light);
        rings.draw(glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), glm::vec3(0.0f, 1.2f, -1.0f)), camera,
                   light);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    void setOutput(ColorOutput output) {
        renderer.setColorOutput(output);
        rings.setColorOutput(output);
    }
    OceanEffect ocean;
    Mesh plane{makePlane({.size = 10.0f})};
    SurfaceRenderer renderer;
    PlanetRings rings;
    Camera camera;
    DirectionalLight light{.direction = {0.0f, 0.25f, -1.0f}, .color = {1.0f, 0.9f, 0.75f}, .ambient = {0.35f, 0.42f, 0.5f}};
};

TEST_F(ColorOutputTest, AFloatTargetGetsLinearUnclampedColoursThatEncodeToTheDisplayOnes) {
    SunlitSea sea(cl());
    const Target display(GL_RGBA8), hdr(GL_RGBA16F);
    sea.draw(display);
    sea.draw(hdr); // Auto: linear, for the float target
    const std::vector<glm::vec3> d = display.read(), l = hdr.read();
    size_t above = 0, apart = 0;
    float worst = 0.0f;
    for (size_t i = 0; i < d.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(l[i][c]) && l[i][c] >= 0.0f) << "pixel " << i << ": " << l[i][c];
            above += l[i][c] > 1.0f;
            // The water's display values roll its highlights off above a knee (shade/water.glsl),
            // which linear output leaves to the engine's tone mapping.
            const float e = std::min(std::abs(displayValue(l[i][c]) - d[i][c]), std::abs(displayValue(waterRollOff(l[i][c])) - d[i][c]));
            worst = std::max(worst, e);
            apart += e > 1.5f / 255.0f; // a byte's rounding, and the rings' copy of an 8-bit frame
        }
    EXPECT_GT(above, d.size() / 200) << "the glint is not brighter than white in linear light";
    EXPECT_LT(apart, d.size() / 100) << "worst " << worst * 255.0f << " levels";
    EXPECT_LT(worst, 4.0f / 255.0f);

    // Display forced on the float target: the 8-bit frame's values.
    sea.setOutput(ColorOutput::Display);
    sea.draw(hdr);
    const std::vector<glm::vec3> forced = hdr.read();
    float forcedWorst = 0.0f;
    for (size_t i = 0; i < d.size(); ++i)
        for (int c = 0; c < 3; ++c) forcedWorst = std::max(forcedWorst, std::abs(forced[i][c] - d[i][c]));
    EXPECT_LT(forcedWorst, 1.0f / 255.0f);
}

TEST_F(ColorOutputTest, AnSrgbTargetThatGlEncodesGetsLinearColours) {
    // GL_FRAMEBUFFER_SRGB on, an sRGB target: GL encodes what the draws write, so they write linear
    // light (Auto). Decoded, its bytes are the float frame's light clamped to 1; written as display
    // values, they would be encoded twice: far too bright.
    SunlitSea sea(cl());
    const Target srgb(GL_SRGB8_ALPHA8), hdr(GL_RGBA16F);
    sea.draw(hdr);
    glEnable(GL_FRAMEBUFFER_SRGB);
    sea.draw(srgb);
    const std::vector<glm::vec3> encoded = srgb.read();
    sea.setOutput(ColorOutput::Display);
    sea.draw(srgb);
    const std::vector<glm::vec3> twice = srgb.read();
    glDisable(GL_FRAMEBUFFER_SRGB);
    const std::vector<glm::vec3> l = hdr.read();
    double error = 0.0, errorTwice = 0.0;
    for (size_t i = 0; i < l.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float light = std::min(l[i][c], 1.0f);
            error += std::abs(srgbDecode(encoded[i][c]) - light);
            errorTwice += std::abs(srgbDecode(twice[i][c]) - light);
        }
    error /= 3.0 * double(l.size());
    errorTwice /= 3.0 * double(l.size());
    EXPECT_LT(error, 0.004) << "mean |decoded - linear|";
    EXPECT_GT(errorTwice, 20.0 * error) << "encoded twice, the frame would be no brighter";
}

} // namespace
} // namespace hfx::test
