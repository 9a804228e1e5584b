// The exact tracer's beam start (DrawOptions::beamStart): the renderer's prepass over blocks of
// pixels must change no hit wherever the draw's viewport sits, for the camera and a shadow map,
// and give back the GL state it found. It runs only on one flat patch (tests/MeshTest.cpp,
// FlatPatch).

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/compute/StaticField.h"
#include "hfx/core/Gl.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/ShadowMap.h"
#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/tools/AccuracyProbe.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hfx::test {
namespace {

class BeamStart : public DeviceTest {};

struct Traced {
    std::vector<glm::vec4> trace; ///< (u, v, depth fraction, fetches + lit / 2), bottom row first
    GLint framebuffer = 0, viewport[4] = {};
    GLboolean blend = GL_FALSE, scissor = GL_FALSE, mask[4] = {};
};

TEST_F(BeamStart, AnOffsetViewportGetsTheSameHitsInFewerFetchesAndItsStateBack) {
    // A viewport whose origin and size are no multiples of the block (the prepass maps the
    // window's pixels onto its blocks from the window's origin, not the viewport's), inside a
    // scissor, with blending on: the hits must be the walk's own, the state the caller's.
    constexpr int N = 64, width = 203, height = 117;
    const std::vector<float> heights = sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}});
    StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const Mesh plane(makePlane({.size = 2.0f}));
    ASSERT_TRUE(plane.flatPatch());
    const SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f, .shadows = false};
    SurfaceRenderer renderer;
    RenderTarget target(width, height, true);
    auto draw = [&](double angle, bool beam) {
        target.bind();
        target.clear();
        glViewport(13, 5, 171, 101);
        glEnable(GL_SCISSOR_TEST);
        glScissor(13, 5, 171, 101);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ZERO);
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE); // the colour's alpha only: the trace is whole
        const Camera camera = cameraAtAngle(angle, 1.6f, 171.0f / 101.0f);
        renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, {},
                      {.technique = Technique::Hierarchical, .traceOutput = true, .beamStart = beam,
                       .tracePass = deviceTracePass()});
        Traced t;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &t.framebuffer);
        glGetIntegerv(GL_VIEWPORT, t.viewport);
        t.blend = glIsEnabled(GL_BLEND);
        t.scissor = glIsEnabled(GL_SCISSOR_TEST);
        glGetBooleani_v(GL_COLOR_WRITEMASK, 0, t.mask);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        t.trace = target.readTrace();
        return t;
    };
    for (double angle : {50.0, 78.0}) {
        const Traced walked = draw(angle, false), started = draw(angle, true);
        EXPECT_EQ(GLuint(started.framebuffer), target.framebuffer());
        EXPECT_EQ(started.viewport[0], 13);
        EXPECT_EQ(started.viewport[1], 5);
        EXPECT_EQ(started.viewport[2], 171);
        EXPECT_EQ(started.viewport[3], 101);
        EXPECT_TRUE(started.blend);
        EXPECT_TRUE(started.scissor);
        EXPECT_FALSE(started.mask[3]);
        size_t drawn = 0, apart = 0;
        double fetchesWalked = 0.0, fetchesStarted = 0.0;
        for (size_t i = 0; i < walked.trace.size(); ++i) {
            const glm::vec4 &w = walked.trace[i], &s = started.trace[i];
            ASSERT_EQ(w.w == 0.0f, s.w == 0.0f) << "pixel " << i << " drawn by one draw only";
            if (w.w == 0.0f) continue;
            ++drawn;
            fetchesWalked += std::floor(w.w);
            fetchesStarted += std::floor(s.w);
            // The same hit, to the rounding of a walk that reaches the hit's cell from elsewhere.
            if (std::abs(w.x - s.x) * N > 1e-3f || std::abs(w.y - s.y) * N > 1e-3f || std::abs(w.z - s.z) > 1e-4f)
                ++apart;
        }
        ASSERT_GT(drawn, size_t(171 * 101 / 2)) << angle;
        EXPECT_EQ(apart, 0u) << "of " << drawn << " pixels at " << angle << " degrees";
        std::printf("%.0f degrees: %zu pixels, fetches %.2f walked, %.2f from the beam start\n", angle, drawn,
                    fetchesWalked / double(drawn), fetchesStarted / double(drawn));
        // Measured: 20% fewer at 50 degrees, 2% at 78 (a block there spans many texels).
        EXPECT_LT(fetchesStarted, (angle < 60.0 ? 0.9 : 1.0) * fetchesWalked) << angle;
    }
}

TEST_F(BeamStart, AShadowMapCastsTheSameTracedDepthWithItAsWithout) {
    // drawShadow traces the light's parallel rays; the prepass finds its blocks' rays from the
    // screen through the patch's projective map, where an orthographic light's eye is one
    // direction. The traced depth the map holds must be the walk's from the top, texel for texel.
    constexpr int N = 64, size = 256;
    const std::vector<float> heights = sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}});
    StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const Mesh plane(makePlane({.size = 2.0f}));
    const SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f, .shadows = false};
    SurfaceRenderer renderer;
    for (const glm::vec3 towardsLight : {glm::vec3(0.3f, 1.0f, 0.2f), glm::vec3(-0.9f, 0.35f, 0.5f)}) {
        std::vector<float> depth[2];
        size_t texels = 0;
        for (int beam = 0; beam < 2; ++beam) {
            ShadowMap map(size);
            map.fit(towardsLight, {0.0f, 0.0f, 0.0f}, 1.5f);
            map.begin();
            renderer.drawShadow(plane, glm::mat4(1.0f), surface.textures(), material, map,
                                {.technique = Technique::Hierarchical, .beamStart = beam == 1,
                                 .tracePass = deviceTracePass()});
            map.end();
            depth[beam].resize(size_t(size) * size);
            glGetTextureImage(map.texture(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(depth[beam].size() * sizeof(float)),
                              depth[beam].data());
        }
        size_t apart = 0;
        for (size_t i = 0; i < depth[0].size(); ++i) {
            if (depth[0][i] < 1.0f) ++texels;
            if (std::abs(depth[0][i] - depth[1][i]) > 1e-6f) ++apart;
        }
        // The plane covers 42% of the map under the high light, 14% under the grazing one.
        ASSERT_GT(texels, size_t(size * size / 10)) << "the plane covers too little of the map";
        EXPECT_EQ(apart, 0u) << "of " << texels << " texels, light (" << towardsLight.x << ", " << towardsLight.y << ", "
                             << towardsLight.z << ")";
    }
}

} // namespace
} // namespace hfx::test
