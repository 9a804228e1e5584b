// The exact tracer's unit (ExactTracer): it decides the texel shadows from the view it is given
// (no caller asks), draws them once for a surface's heights and light, and draws them again when
// either changes.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/compute/StaticField.h"
#include "hfx/core/Gl.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace hfx::test {
namespace {

class ExactTracerTest : public DeviceTest {};

TEST_F(ExactTracerTest, TheViewDecidesTheTexelShadowsWhichLastAsLongAsTheirHeightsAndLight) {
    // A 64² field on a 320x180 image: seen from near, the plane shows on several pixels per
    // texel and the texel shadows pay (drawn at every sample); from far, on well under one, and
    // they do not. Off and On override the view. Spoiling the drawn texels changes the next
    // frame only while the tracer keeps them (same heights, same light); new heights or a moved
    // light redraw them, which puts the frame back.
    constexpr int N = 64;
    const std::vector<float> heights = sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}});
    StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false, .pyramid = true}));
    surface.run(field.buffer());
    const Mesh plane(makePlane({.size = 2.0f}));
    const SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f};
    DirectionalLight light;
    light.direction = {0.7f, 0.45f, 0.3f}; // low: long shadows
    SurfaceRenderer renderer;
    RenderTarget target(320, 180);
    Camera nearCamera = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.6f, 0.3f, 1.2f);
    Camera farCamera = Camera::orbit({0.0f, 0.0f, 0.0f}, 40.0f, 0.3f, 1.2f);
    nearCamera.aspect = farCamera.aspect = 320.0f / 180.0f;
    auto draw = [&](const Camera& camera, TexelShadowChoice choice, const DirectionalLight& l) {
        target.bind();
        target.clear();
        renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, l,
                      {.technique = Technique::Hierarchical, .texelShadows = choice});
        return target.readColor().pixels;
    };

    const std::vector<float> walked = draw(nearCamera, TexelShadowChoice::Off, light);
    EXPECT_EQ(renderer.tracer().last().texelStride, 0);
    EXPECT_GT(renderer.tracer().last().pixelsPerTexel, 1.75);
    const std::vector<float> read = draw(nearCamera, TexelShadowChoice::Auto, light);
    const TracerFrame nearFrame = renderer.tracer().last();
    EXPECT_EQ(nearFrame.texelStride, 1) << nearFrame.pixelsPerTexel << " pixels per texel";
    ASSERT_NE(nearFrame.texelShadows, nullptr);
    EXPECT_NE(read, walked) << "the frame does not show the texel shadows";

    draw(farCamera, TexelShadowChoice::Auto, light);
    EXPECT_EQ(renderer.tracer().last().texelStride, 0);
    EXPECT_LT(renderer.tracer().last().pixelsPerTexel, 0.5);
    draw(farCamera, TexelShadowChoice::On, light);
    EXPECT_EQ(renderer.tracer().last().texelStride, 1);

    // Spoiled while kept: the next frame reads the spoiled ones.
    auto spoil = [&] {
        const TexelShadows* kept = renderer.tracer().last().texelShadows;
        ASSERT_NE(kept, nullptr);
        const std::vector<float> lit(size_t(N) * N, 0.0f);
        HFX_GL_CHECK(glTextureSubImage2D(kept->texture(), 0, 0, 0, N, N, GL_RED, GL_FLOAT, lit.data()));
    };
    draw(nearCamera, TexelShadowChoice::Auto, light);
    spoil();
    EXPECT_NE(draw(nearCamera, TexelShadowChoice::Auto, light), read) << "the texel shadows were drawn again";
    // The same heights, uploaded into the other pair and back into this one: the tracer cannot
    // know they are the same.
    const SurfaceTextures* before = &surface.textures();
    surface.run(field.buffer());
    surface.run(field.buffer());
    ASSERT_EQ(&surface.textures(), before);
    const std::vector<float> redrawn = draw(nearCamera, TexelShadowChoice::Auto, light);
    EXPECT_EQ(redrawn, read) << "texel shadows kept past new heights";
    spoil();
    DirectionalLight moved = light;
    moved.direction.z += 0.05f;
    const std::vector<float> movedOnce = draw(nearCamera, TexelShadowChoice::Auto, moved);
    EXPECT_EQ(draw(nearCamera, TexelShadowChoice::Auto, moved), movedOnce);
    EXPECT_EQ(draw(nearCamera, TexelShadowChoice::Auto, light), read) << "texel shadows kept past a moved light";
}

} // namespace
} // namespace hfx::test
