// The exact tracer's unit (ExactTracer): it holds every surface's height bounds and decides the
// texel shadows from the view it is given (no caller asks), draws them once for a surface's
// heights and light, and draws them again when either changes.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/compute/StaticField.h"
#include "hfx/core/Gl.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/tracer/HeightBounds.h"
#include "hfx/tools/AccuracyProbe.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

namespace hfx::test {
namespace {

class ExactTracerTest : public DeviceTest {};

/// A plane of relief under a low light (long shadows), and a smaller plane nearer over part of it.
struct CoveredPlane {
    Mesh plane{makePlane({.size = 2.0f})};
    Mesh cover{makePlane({.size = 0.6f})};
    SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f};
    DirectionalLight light{.direction = {0.7f, 0.45f, 0.3f}};
    glm::mat4 nearer = glm::translate(glm::mat4(1.0f), glm::vec3(-0.3f, 0.35f, 0.2f));
};

/// Two draws' trace outputs and colours, pixel by pixel: the one that walks in the draw (a) and
/// the one whose walks ran in the compute pass (b). On llvmpipe the two rays are the same to the
/// bit (its interpolation is the screen map's arithmetic) and so are the hits; on a GPU the draw's
/// ray is its rasteriser's rounding, and a walk carries it to the hit: within kDrawHitTexels /
/// 5 and a thousandth of the relief's depth, or it counts as another hit (the H200: 1709 of
/// 21916 grazing pixels more than 0.001 texels apart, 0 on llvmpipe).
struct WalksCompared {
    static constexpr float kHitTexels = float(kDrawHitTexels) / 5.0f;
    size_t traced = 0, hitsOff = 0, shadowsOff = 0, colours = 0, channels = 0, sameUntraced = 0, untraced = 0,
           drawn = 0;
    double fetchesWalked = 0.0, fetchesComputed = 0.0, worstHit = 0.0;

    WalksCompared(const std::vector<glm::vec4>& walked, const std::vector<glm::vec4>& computed, const Image& walkedColor,
                  const Image& computedColor, int fieldSize) {
        for (size_t i = 0; i < walked.size(); ++i) {
            const glm::vec4 a = walked[i], b = computed[i];
            drawn += a != glm::vec4(0.0f);
            if (a.z <= 0.0f) { // the background, another mesh, or normal mapped: the same in both
                ++untraced;
                sameUntraced += a == b;
                continue;
            }
            ++traced;
            const float apart = glm::length(glm::vec2(a) - glm::vec2(b)) * float(fieldSize);
            worstHit = std::max(worstHit, double(apart));
            hitsOff += apart > kHitTexels || std::abs(a.z - b.z) > 1e-3f;
            const float litA = 2.0f * (a.w - std::floor(a.w)), litB = 2.0f * (b.w - std::floor(b.w));
            shadowsOff += std::abs(litA - litB) > 1e-3f;
            fetchesWalked += std::floor(a.w);
            fetchesComputed += std::floor(b.w);
        }
        channels = walkedColor.pixels.size();
        for (size_t i = 0; i < channels; ++i)
            colours += std::abs(walkedColor.pixels[i] - computedColor.pixels[i]) > 1.0f / 255.0f + 1e-6f;
    }
    void print(const std::string& what) const {
        std::printf("[computed walks] %s: %zu traced pixels, %zu hits (%.2g texels apart at most) and %zu shadows "
                    "differ, %zu colour channels by more than 1/255; fetches %.2f walked in the draw, %.2f computed\n",
                    what.c_str(), traced, hitsOff, worstHit, shadowsOff, colours,
                    fetchesWalked / double(std::max<size_t>(traced, 1)),
                    fetchesComputed / double(std::max<size_t>(traced, 1)));
    }
    /// The bounds both tests hold the pass to: one pixel in 2,000 (none differ where measured).
    void expectAlike() const {
        EXPECT_EQ(sameUntraced, untraced) << "pixels not traced in the draw differ";
        EXPECT_LE(hitsOff, traced / 2000);
        EXPECT_LE(shadowsOff, traced / 2000);
        EXPECT_LE(colours, channels / 2000);
        EXPECT_NEAR(fetchesComputed, fetchesWalked, 0.002 * fetchesWalked);
    }
};

TEST_F(ExactTracerTest, TheViewDecidesTheTexelShadowsWhichLastAsLongAsTheirHeightsAndLight) {
    // A 64² field on a 320x180 image: seen from near, the plane shows on several pixels per
    // texel and the texel shadows pay (drawn at every sample); from far, on well under one, and
    // they do not. Off and On override the view. Spoiling the drawn texels changes the next
    // frame only while the tracer keeps them (same heights, same light); new heights or a moved
    // light redraw them, which puts the frame back. With the walks in a compute pass they do not
    // pay (a GPU's): Auto leaves them off there, and On draws them.
    constexpr int N = 64;
    const std::vector<float> heights = sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}});
    StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
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
    auto draw = [&](const Camera& camera, TexelShadowChoice choice, const DirectionalLight& l,
                    TracePass pass = TracePass::InDraw) {
        target.bind();
        target.clear();
        renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, l,
                      {.technique = Technique::Hierarchical, .texelShadows = choice, .tracePass = pass});
        EXPECT_EQ(renderer.tracer().last().computeTrace, pass == TracePass::Compute);
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
    draw(nearCamera, TexelShadowChoice::Auto, light, TracePass::Compute);
    EXPECT_EQ(renderer.tracer().last().texelShadows, nullptr) << "read with the walks in a compute pass";
    EXPECT_GT(renderer.tracer().last().pixelsPerTexel, 1.75);
    const std::vector<float> computedRead =
        draw(nearCamera, TexelShadowChoice::On, light, TracePass::Compute);
    EXPECT_EQ(renderer.tracer().last().texelStride, 1);
    EXPECT_NE(renderer.tracer().last().texelShadows, nullptr);
    EXPECT_NE(computedRead, draw(nearCamera, TexelShadowChoice::Off, light, TracePass::Compute))
        << "the computed frame does not show the texel shadows";

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

TEST_F(ExactTracerTest, ItReadsAProducersBoundsWhereTheyHoldAndItsOwnElsewhere) {
    // Where the compute device builds a surface's bounds (GlWorkarounds::pyramidFromCompute,
    // forced on here), the first hier draw builds the tracer's own and notes the pipeline's as
    // read; the pipeline's next frame carries them, and the tracer reads them: spoiled bounds
    // change the frame, the next frame's put it back. Drawn without the pipeline's, the tracer
    // holds its own again; once no draw reads them, the device stops building them.
    const WorkaroundsSet set("pyramid-from-compute=1");
    constexpr int N = 64;
    StaticField field(cl(), N, N, EdgeMode::Wrap, sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}}));
    // Float32 texels: the device builds only those bounds (their heights are its own).
    SurfacePipeline surface(
        cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false, .format = SurfaceFormat::Float32}));
    surface.run(field.buffer());
    ASSERT_NE(surface.bounds(), nullptr);
    const Mesh plane(makePlane({.size = 2.0f}));
    const SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f};
    DirectionalLight light;
    light.direction = {0.7f, 0.45f, 0.3f};
    SurfaceRenderer renderer;
    RenderTarget target(160, 90);
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.5f, 0.3f, 1.0f);
    camera.aspect = 160.0f / 90.0f;
    auto draw = [&](bool withTheirs) {
        target.bind();
        target.clear();
        const SurfaceLayer layer{.textures = &surface.textures(), .bounds = withTheirs ? surface.bounds() : nullptr};
        renderer.draw(plane, glm::mat4(1.0f), std::span(&layer, 1), material, camera, light,
                      {.technique = Technique::Hierarchical, .beamStart = false,
                       .texelShadows = TexelShadowChoice::Off, .tracePass = deviceTracePass()});
        return target.readColor().pixels;
    };
    const std::vector<float> own = draw(true); // the tracer's, built from the texels
    EXPECT_FALSE(surface.bounds()->holds(surface.textures()));
    surface.run(field.buffer()); // read by that draw: the device builds them
    ASSERT_TRUE(surface.bounds()->holds(surface.textures()));
    EXPECT_EQ(draw(true), own) << "the device's bounds draw otherwise than GL's";

    // Bounds with every cell's top at the floor: rays that trust them walk to the floor.
    size_t floats = 0;
    for (int level = 0; level < surface.bounds()->levels(); ++level)
        floats += 2 * size_t(std::max(N >> level, 1)) * size_t(std::max(N >> level, 1));
    const std::vector<float> floor(floats, 0.0f);
    surface.bounds()->upload(floor.data(), surface.textures());
    EXPECT_NE(draw(true), own) << "the tracer did not read the pipeline's bounds";
    EXPECT_EQ(draw(false), own) << "its own bounds, drawn without the pipeline's";
    surface.run(field.buffer()); // noted as read by the spoiled draw: the device builds them
    ASSERT_TRUE(surface.bounds()->holds(surface.textures()));
    EXPECT_EQ(draw(true), own);
    surface.run(field.buffer()); // noted by that draw
    surface.run(field.buffer()); // by none
    surface.run(field.buffer());
    EXPECT_FALSE(surface.bounds()->holds(surface.textures())) << "built though no draw read them";
    EXPECT_EQ(draw(true), own);
}

TEST_F(ExactTracerTest, TheLightWalksItsTexelShadowsLeaveAreWalkedAfterTheDrawIntoTheSamePixels) {
    // The near view of the first test, texel shadows at every sample: a ray whose four samples
    // disagree (the hard shadow's edge crosses its cell) is appended by the draw and walked after
    // it (DrawOptions::deferShadowWalks, ExactTracer::finish). The frame must be the one whose
    // draw walks those rays itself, to the 8-bit target's rounding; until the pass writes them,
    // those pixels hold the texel shadows' blend, which differs there (so a pass that wrote
    // nothing, or the wrong pixels, fails). A plane drawn first, nearer and opaque, hides part of
    // the relief: the relief's fragments behind it append their rays too, and the pass must not
    // write them through it (its depth test). At 64x36 the buffer first holds 256 rays, fewer
    // than the draw appends: the rest walk in the draw, and the frame is still the same; the
    // next deferring draw has room for more (the count read back once the GPU was past it), up to
    // a ray per 4 pixels (the rough field appends one for half of them).
    // In both layouts of the bounds: the pass's walk is compiled for each.
    constexpr int N = 64;
    const CoveredPlane scene;
    const auto &plane = scene.plane, &cover = scene.cover;
    const auto& material = scene.material;
    const auto& light = scene.light;
    const auto& nearer = scene.nearer;
    for (const int size : {320, 64}) {
        SCOPED_TRACE(str(size, "x", size * 9 / 16));
        // At 64x36 a rougher field: more of its cells hold a shadow's edge than the buffer holds rays.
        const std::vector<float> heights = size == 320 ? sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}})
                                                       : sumOfSines(N, {{0.3, 9, 7, 0.0}, {0.2, -11, 13, 0.7}});
        StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
        SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
        surface.run(field.buffer());
        RenderTarget target(size, size * 9 / 16);
        Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.6f, 0.3f, 1.2f);
        camera.aspect = 16.0f / 9.0f;
        // Both layouts of the bounds: the mip chain is what a GPU reads, the atlas llvmpipe's.
        for (const PyramidLayout layout : {PyramidLayout::MipChain, PyramidLayout::Atlas}) {
            SCOPED_TRACE(layout == PyramidLayout::Atlas ? "atlas" : "mip chain");
            SurfaceRenderer renderer;
            auto draw = [&](bool defer, bool covered) {
                target.bind();
                target.clear();
                if (covered)
                    renderer.draw(cover, nearer, surface.textures(), material, camera, light,
                                  {.technique = Technique::NormalMapping});
                renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, light,
                              {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::On,
                               .deferShadowWalks = defer, .tracePass = TracePass::InDraw, .boundsLayout = layout});
                EXPECT_EQ(renderer.tracer().last().deferredShadows, defer);
                EXPECT_EQ(renderer.tracer().last().atlas, layout == PyramidLayout::Atlas);
                return target.readColor();
            };
            for (const bool covered : {false, true}) {
                SCOPED_TRACE(covered ? "covered in part" : "uncovered");
                const Image inDraw = draw(false, covered);
                const Image deferred = draw(true, covered);
                const int walks = renderer.tracer().deferredWalks(), capacity = renderer.tracer().deferredCapacity();
                ASSERT_EQ(inDraw.pixels.size(), deferred.pixels.size());
                double worst = 0.0;
                size_t differ = 0;
                for (size_t i = 0; i < inDraw.pixels.size(); ++i) {
                    const double d = std::abs(double(inDraw.pixels[i]) - deferred.pixels[i]);
                    worst = std::max(worst, d);
                    differ += d > 0.0;
                }
                std::printf("[deferred walks] %dx%d%s, %s: %d rays appended, room for %d; %zu of %zu channels differ, by "
                            "%.4f at most\n",
                            inDraw.width, inDraw.height, covered ? ", covered in part" : "",
                            layout == PyramidLayout::Atlas ? "atlas" : "mip chain", walks, capacity, differ,
                            inDraw.pixels.size(), worst);
                EXPECT_GT(walks, size == 64 ? 256 : 300) << "too few rays deferred to tell";
                if (size == 64 && !covered) EXPECT_GT(walks, capacity) << "the walks past the buffer's room not tried";
                else // room for what the last draw appended, up to a ray per 4 pixels (64x36: 576 of 1238)
                    EXPECT_GE(capacity, std::min(walks, inDraw.width * inDraw.height / 4))
                        << "the buffer did not grow to what the last draw appended";
                // Measured: none differ. Without the pass 394 channels of the 320x180 frame differ,
                // by up to 3/255; with it writing through the nearer plane, 360 by up to 77/255.
                EXPECT_LE(worst, 1.0 / 255.0 + 1e-6);
                EXPECT_LE(differ, inDraw.pixels.size() / 10000);
            }
        }
        // Water's colour is not affine in the light (its highlights roll off): its walks stay in
        // the draw.
        SurfaceRenderer renderer;
        SurfaceMaterial water = material;
        water.shading = Shading::Water;
        target.bind();
        renderer.draw(plane, glm::mat4(1.0f), surface.textures(), water, camera, light,
                      {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::On,
                       .deferShadowWalks = true});
        EXPECT_NE(renderer.tracer().last().texelShadows, nullptr);
        EXPECT_FALSE(renderer.tracer().last().deferredShadows);
    }
}

TEST_F(ExactTracerTest, ItSaysTheMemoryItHoldsAndLetsGoOfItAll) {
    // What an engine's budget counts: the bounds of the surface drawn (its pyramid, and the atlas
    // layout's cells), its texel shadows, the beam start's target (a texel per 8x8-pixel block),
    // and the compute pass's slots: 24 bytes a pixel, 32 once a sphere stored its light rays,
    // three planes of them under a triplanar mapping. release() lets go of all of it, and the next
    // draw makes what it needs again: the same frame.
    constexpr int N = 64, W = 320, H = 180;
    StaticField field(cl(), N, N, EdgeMode::Wrap, sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}}));
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const Mesh plane(makePlane({.size = 2.0f}));
    const Mesh sphere(makeSphere({}));
    SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.7f, 0.45f, 0.3f}};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.6f, 0.3f, 1.2f);
    camera.aspect = float(W) / float(H);
    RenderTarget target(W, H, true);
    SurfaceRenderer renderer;
    EXPECT_EQ(renderer.tracer().memory().total(), 0u) << "before any draw";
    const auto draw = [&](const Mesh& mesh, TracePass pass) {
        target.bind();
        target.clear();
        renderer.draw(mesh, glm::mat4(1.0f), surface.textures(), material, camera, light,
                      {.technique = Technique::Hierarchical,
                       .texelShadows = TexelShadowChoice::On,
                       .tracePass = pass});
        EXPECT_EQ(renderer.tracer().last().computeTrace, pass == TracePass::Compute);
        return target.readColor().pixels;
    };
    draw(plane, TracePass::InDraw);
    const TracerMemory drawn = renderer.tracer().memory();
    size_t pyramid = 0;
    if (resolvedLayout(PyramidLayout::Auto) == PyramidLayout::Atlas) {
        const auto [w, h] = HeightBounds::atlasSize(N, N);
        pyramid = size_t(w) * h * 8 + size_t(N) * N * 16; // RG32F levels, RGBA32F cells
    } else {
        for (int n = N; n >= 1; n /= 2) pyramid += size_t(n) * n * 8;
    }
    EXPECT_EQ(drawn.bounds, pyramid);
    EXPECT_EQ(drawn.texelShadows, size_t(N) * N * 4);
    const size_t blocks = size_t((W + kBeamBlock - 1) / kBeamBlock) * ((H + kBeamBlock - 1) / kBeamBlock);
    EXPECT_EQ(drawn.prepasses, blocks * 4);
    EXPECT_EQ(drawn.slots, 0u) << "the walks in the draw";
    const std::vector<float> computed = draw(plane, TracePass::Compute);
    EXPECT_EQ(renderer.tracer().memory().slots, size_t(W) * H * 24);
    draw(sphere, TracePass::Compute);
    EXPECT_EQ(renderer.tracer().memory().slots, size_t(W) * H * 32) << "with its light rays";
    material.triplanar = {.scale = 1.5f, .sharpness = 2.0f};
    draw(sphere, TracePass::Compute);
    EXPECT_EQ(renderer.tracer().memory().slots, size_t(W) * H * 3 * 32) << "three planes";
    const TracerMemory most = renderer.tracer().memory();
    std::printf("[tracer memory] %dx%d, %d² field: bounds %zu, texel shadows %zu, prepasses %zu, "
                "slots %zu bytes\n",
                W, H, N, most.bounds, most.texelShadows, most.prepasses, most.slots);

    renderer.tracer().release();
    EXPECT_EQ(renderer.tracer().memory().total(), 0u) << "after release()";
    material.triplanar = {};
    EXPECT_EQ(draw(plane, TracePass::Compute), computed) << "the frame after release()";
    const TracerMemory again = renderer.tracer().memory();
    EXPECT_EQ(again.slots, size_t(W) * H * 24);
    EXPECT_EQ(again.bounds, pyramid);
    EXPECT_EQ(again.texelShadows, size_t(N) * N * 4);
}

TEST_F(ExactTracerTest, TheWalksInAComputePassGiveTheDrawsHitsShadowsAndColours) {
    // TracePass::Compute (trace/hier/trace.glsl) on a flat patch: the compute pass finds each
    // pixel's view ray from the screen (the patch's texcoords are a projective map of it, as a
    // rasteriser's perspective-correct interpolation has them; no rays draw), walks it and its
    // light ray, the shading draw reads the hit. Every pixel must show what the draw that walks
    // its own rays shows: the hit (uv, depth), the self-shadow, the fetches and the colour, with
    // and without texel shadows and the beam start, in both layouts of the bounds, where a nearer
    // plane hides part of the relief (the pass walks the hidden pixels too: the shading draw must
    // leave them to it), in a viewport offset into the target (the slots count from its
    // origin), for two views in a row (a slot of the first view must not serve the second).
    // A shading draw that read nothing, or the wrong slots, shows uv (0, 0) or another pixel's hit.
    // A smooth field, and blocks (plateaus with sharp edges, which a light ray can graze: the
    // pass's light ray is the flat patch's, the draw's turned by the pixel's interpolated frame).
    // Measured: none differ on either.
    constexpr int N = 64;
    struct Case {
        const char* name;
        std::vector<float> heights;
    };
    const Case cases[] = {{"smooth", sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}})}, {"blocks", blocks(N, 4)}};
    const CoveredPlane scene;
    const auto &plane = scene.plane, &cover = scene.cover;
    const auto& material = scene.material;
    const auto& light = scene.light;
    const auto& nearer = scene.nearer;
    constexpr int W = 320, H = 180, X0 = 24, Y0 = 16, VW = 256, VH = 144;
    RenderTarget target(W, H, true);
    Camera nearView = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.6f, 0.3f, 1.2f);
    Camera grazing = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.4f, -0.6f, 0.25f);
    nearView.aspect = grazing.aspect = float(VW) / float(VH);
    for (const Case& c : cases) {
        StaticField field(cl(), N, N, EdgeMode::Wrap, c.heights);
        SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
        surface.run(field.buffer());
        for (const PyramidLayout layout : {PyramidLayout::MipChain, PyramidLayout::Atlas})
            for (const TexelShadowChoice texels : {TexelShadowChoice::Off, TexelShadowChoice::On})
                for (const bool beam : {true, false}) {
                    const std::string what = str(c.name, ", ", layout == PyramidLayout::Atlas ? "atlas" : "mip chain",
                                                 texels == TexelShadowChoice::On ? ", texel shadows" : "",
                                                 beam ? ", beam start" : "");
                    SCOPED_TRACE(what);
                    SurfaceRenderer renderer;
                    auto draw = [&](const Camera& camera, TracePass pass) {
                        target.bind();
                        target.clear();
                        glViewport(X0, Y0, VW, VH);
                        renderer.draw(cover, nearer, surface.textures(), material, camera, light,
                                      {.technique = Technique::NormalMapping, .traceOutput = true});
                        renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, light,
                                      {.technique = Technique::Hierarchical, .traceOutput = true, .beamStart = beam,
                                       .texelShadows = texels, .tracePass = pass, .boundsLayout = layout});
                        EXPECT_EQ(renderer.tracer().last().computeTrace, pass == TracePass::Compute);
                        EXPECT_EQ(renderer.tracer().last().beamStart, beam);
                        return std::pair(target.readTrace(), target.readColor());
                    };
                    for (const Camera* camera : {&nearView, &grazing}) {
                        SCOPED_TRACE(camera == &nearView ? "near view" : "grazing view");
                        const auto [walkedTrace, walkedColor] = draw(*camera, TracePass::InDraw);
                        const auto [computedTrace, computedColor] = draw(*camera, TracePass::Compute);
                        EXPECT_TRUE(renderer.tracer().last().patchRays) << "a flat patch";
                        const WalksCompared compared(walkedTrace, computedTrace, walkedColor, computedColor, N);
                        compared.print(str(what, ", ", camera == &nearView ? "near" : "grazing"));
                        EXPECT_GT(compared.traced, size_t(VW * VH / 2)) << "too little relief to tell";
                        compared.expectAlike();
                    }
                }
    }
    StaticField field(cl(), N, N, EdgeMode::Wrap, cases[0].heights);
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    // Where the two draws could meet a pixel more or less than once each, the draw walks.
    SurfaceRenderer renderer;
    target.bind();
    glEnable(GL_STENCIL_TEST);
    renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, nearView, light,
                  {.technique = Technique::Hierarchical, .tracePass = TracePass::Compute});
    glDisable(GL_STENCIL_TEST);
    EXPECT_FALSE(renderer.tracer().last().computeTrace) << "under a stencil test";
    MeshData undeclared = makeSphere({});
    undeclared.convex = false; // its front faces might overlap: two fragments a pixel
    const Mesh mayOverlap(undeclared);
    renderer.draw(mayOverlap, glm::mat4(1.0f), surface.textures(), material, nearView, light,
                  {.technique = Technique::Hierarchical, .tracePass = TracePass::Compute});
    EXPECT_FALSE(renderer.tracer().last().computeTrace) << "on a mesh not said to be convex";
}

TEST_F(ExactTracerTest, TheComputedWalksHoldOnASphereAndUnderASilhouetteFade) {
    // A convex mesh (Mesh::convex) takes the compute pass with a rays draw: its front faces
    // meet each pixel once, and a back face's fragment stores nothing and is normal mapped. Where
    // the light is not one for the draw (a sphere's frame turns pixel by pixel; a silhouette fade
    // scales the depth, and the light's texcoords per climb with it) the rays draw stores each
    // pixel's light ray (HFX_TRACE_LIGHTS). The sphere with the planet's fade and without, its
    // back faces drawn behind its front (a back face that stored its ray would take a front
    // face's slot), and seen from inside (every fragment a back face's); a plane with a fade (its
    // rays drawn too); a plane whose light has no texel shadows' (its rays and its light from the
    // screen: the pass finds the light ray itself); a plane seen from below, and one the near
    // plane cuts (a slot the pass left that the draw's fragment needed would be discarded).
    // A shading draw that read a back face's or another pixel's slot shows its hit or discards.
    // Measured: none differ (seen from outside, the sphere's back faces are culled in both; before
    // they were, 3 and 7 hits differed, where a back face peeked past a front face's grazing hit
    // at the rim and the draw walked its ray).
    constexpr int N = 64;
    StaticField field(cl(), N, N, EdgeMode::Wrap, sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}}));
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const Mesh sphere(makeSphere({}));
    const Mesh plane(makePlane({.size = 2.0f}));
    const DirectionalLight light{.direction = {0.7f, 0.45f, 0.3f}};
    constexpr int W = 320, H = 180;
    RenderTarget target(W, H, true);
    auto view = [](float distance, float yaw, float pitch, float nearPlane = 0.05f) {
        Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, distance, yaw, pitch);
        camera.aspect = float(W) / float(H);
        camera.nearPlane = nearPlane;
        return camera;
    };
    struct Case {
        const char* name;
        const Mesh* mesh;
        Camera camera;
        float depthScale, fade, sharpness;
        size_t leastTraced; // pixels
        float triplanar = 0.0f; // its scale; 0: the mesh's texcoords
    };
    // (A sharpness of 1 has no flat patch's light either: flatSurfaceLight gives none at or below 1.)
    const Case cases[] = {{"sphere, the planet's fade", &sphere, view(2.4f, 0.4f, 0.3f), 0.02f, 0.25f, 2.0f, 8000},
                          {"sphere, no fade", &sphere, view(2.4f, -1.1f, 0.5f), 0.02f, 0.0f, 2.0f, 8000},
                          {"sphere, from inside", &sphere, view(0.4f, 0.4f, 0.3f), 0.02f, 0.25f, 2.0f, 0},
                          {"plane, a fade", &plane, view(1.6f, 0.3f, 0.5f), 0.1f, 0.3f, 2.0f, W * H / 2},
                          {"plane, a shadow sharpness of 1", &plane, view(1.6f, 0.3f, 0.5f), 0.1f, 0.0f, 1.0f, W * H / 2},
                          // (Its rays from the screen: the slots it finds seen from below marked
                          // normal mapped, and none discarded where the near plane cuts it.)
                          {"plane, seen from below", &plane, view(1.6f, 0.3f, -0.5f), 0.1f, 0.0f, 2.0f, 0},
                          {"plane, cut by the near plane", &plane, view(0.6f, 0.3f, 0.35f, 0.4f), 0.1f, 0.0f, 2.0f,
                           W * H / 4},
                          // (Each projection it weighs walks in its own plane of slots.)
                          {"sphere, a triplanar mapping", &sphere, view(2.4f, 0.4f, 0.3f), 0.04f, 0.0f, 2.0f,
                           8000, 1.5f},
                          {"sphere, a triplanar mapping and a fade", &sphere, view(2.4f, -1.1f, 0.5f), 0.04f, 0.25f,
                           2.0f, 8000, 1.5f}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        SurfaceMaterial material{.depthScale = c.depthScale, .lodThreshold = 100.0f, .silhouetteFade = c.fade};
        material.shadowSharpness = c.sharpness;
        if (c.triplanar > 0.0f) material.triplanar = {.scale = c.triplanar, .sharpness = 2.0f};
        SurfaceRenderer renderer;
        auto draw = [&](TracePass pass) {
            target.bind();
            target.clear();
            // (Texel shadows on in both passes where the patch has a light for them: Auto takes
            // them only in the draw.)
            renderer.draw(*c.mesh, glm::mat4(1.0f), surface.textures(), material, c.camera, light,
                          {.technique = Technique::Hierarchical, .traceOutput = true,
                           .texelShadows = TexelShadowChoice::On, .tracePass = pass});
            // (A plane without a fade has one frame for every pixel: its rays come from the
            // screen, and its light with them.)
            const bool patchRays = pass == TracePass::Compute && c.mesh == &plane && c.fade == 0.0f;
            EXPECT_EQ(renderer.tracer().last().computeTrace, pass == TracePass::Compute);
            EXPECT_EQ(renderer.tracer().last().patchRays, patchRays);
            EXPECT_EQ(renderer.tracer().last().traceLights, pass == TracePass::Compute && !patchRays)
                << "the light is the pixel's here";
            if (pass == TracePass::Compute) {
                EXPECT_EQ(renderer.tracer().last().tracePlanes, c.triplanar > 0.0f ? 3 : 1);
            }
            return std::pair(target.readTrace(), target.readColor());
        };
        const auto [walkedTrace, walkedColor] = draw(TracePass::InDraw);
        const auto [computedTrace, computedColor] = draw(TracePass::Compute);
        const WalksCompared compared(walkedTrace, computedTrace, walkedColor, computedColor, N);
        compared.print(c.name);
        EXPECT_GE(compared.traced, c.leastTraced) << "too little relief to tell";
        if (c.leastTraced == 0) {
            EXPECT_EQ(compared.traced, 0u) << "from inside or below, every face is a back face";
        }
        EXPECT_GT(compared.drawn, size_t(8000)) << "nothing drawn";
        compared.expectAlike();
    }
}


TEST_F(ExactTracerTest, AutoTimesBothPassesOnTheFirstDrawsThenKeepsTheFaster) {
    // TracePass::Auto on a device no workaround decides for (here: trace-in-draw turned off):
    // the first draws that could take either pass alternate them, the compute pass first, each
    // timed, until each has 1 + kCounted draws; every draw after takes the trial's choice, untimed;
    // the choice is the side whose median is faster by the compute pass's margin. Both clocks: the
    // CPU's between two glFinish (a CPU rasteriser's) and GL timestamps read back without waiting
    // (a GPU's; glFinish between the draws here makes each one's ready by the next draw). Each
    // mesh has its trial, camera views and shadow casters apart: two meshes drawn in turn take
    // each side in turn each (one trial for both would give one mesh every compute pass and the
    // other every draw). Where the workaround decides, nothing is timed.
    constexpr int N = 64;
    StaticField field(cl(), N, N, EdgeMode::Wrap, sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.15, -1, 3, 0.7}}));
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const Mesh plane(makePlane({.size = 2.0f}));
    const Mesh inset(makePlane({.size = 0.5f}));
    const glm::mat4 nearer = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.3f, 0.0f));
    const SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.7f, 0.45f, 0.3f}};
    RenderTarget target(160, 90, true);
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.6f, 0.3f, 1.2f);
    camera.aspect = 160.0f / 90.0f;
    constexpr int kTrialDraws = 2 * (TracePassTrial::kWarmUp + TracePassTrial::kCounted);
    for (const char* workarounds : {"trace-in-draw=0,cpu-clock-timer=1", "trace-in-draw=0,cpu-clock-timer=0"}) {
        SCOPED_TRACE(workarounds);
        const WorkaroundsSet set(workarounds);
        SurfaceRenderer renderer;
        std::vector<bool> computed, timed, insetComputed, insetTimed;
        for (int draw = 0; draw < kTrialDraws + 4; ++draw) {
            target.bind();
            target.clear();
            renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, light,
                          {.technique = Technique::Hierarchical});
            glFinish();
            computed.push_back(renderer.tracer().last().computeTrace);
            timed.push_back(renderer.tracer().last().timed);
            renderer.draw(inset, nearer, surface.textures(), material, camera, light,
                          {.technique = Technique::Hierarchical});
            glFinish();
            insetComputed.push_back(renderer.tracer().last().computeTrace);
            insetTimed.push_back(renderer.tracer().last().timed);
        }
        for (int draw = 0; draw < kTrialDraws; ++draw) {
            EXPECT_TRUE(timed[size_t(draw)]) << "draw " << draw;
            EXPECT_EQ(computed[size_t(draw)], draw % 2 == 0) << "draw " << draw << ": the compute pass first, then by turns";
            EXPECT_TRUE(insetTimed[size_t(draw)]) << "the inset's draw " << draw;
            EXPECT_EQ(insetComputed[size_t(draw)], draw % 2 == 0) << "the inset's draw " << draw;
        }
        EXPECT_TRUE(renderer.tracer().passTrial(inset, false).decided());
        const TracePassTrialReport r = renderer.tracer().passTrial(plane, false);
        ASSERT_TRUE(r.decided()) << "after " << kTrialDraws << " timed draws";
        EXPECT_EQ(r.inDrawDraws, TracePassTrial::kCounted);
        EXPECT_EQ(r.computeDraws, TracePassTrial::kCounted);
        EXPECT_EQ(r.chosen == TracePass::Compute, r.computeMs < TracePassTrial::kComputeMargin * r.inDrawMs)
            << r.computeMs << " ms computed, " << r.inDrawMs << " ms in the draw";
        for (int draw = kTrialDraws; draw < kTrialDraws + 4; ++draw) {
            EXPECT_FALSE(timed[size_t(draw)]) << "draw " << draw;
            EXPECT_EQ(computed[size_t(draw)], r.chosen == TracePass::Compute) << "draw " << draw;
        }
        std::printf("[trace pass trial] %s: %s (%.2f ms in the draw, %.2f ms with the compute pass)\n", workarounds,
                    tracePassName(r.chosen), r.inDrawMs, r.computeMs);
        if (std::string(workarounds).ends_with("=1")) {
            EXPECT_GT(r.inDrawMs, 0.0);
            EXPECT_GT(r.computeMs, 0.0);
        }
        const TracePassTrialReport casters = renderer.tracer().passTrial(plane, true);
        EXPECT_FALSE(casters.decided()) << "no shadow caster was drawn";
        EXPECT_EQ(casters.inDrawDraws + casters.computeDraws, 0);
        // A draw that asks for a side is not timed, and the trial's choice does not bind it.
        const TracePass other = r.chosen == TracePass::Compute ? TracePass::InDraw : TracePass::Compute;
        renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, light,
                      {.technique = Technique::Hierarchical, .tracePass = other});
        EXPECT_EQ(renderer.tracer().last().computeTrace, other == TracePass::Compute);
        EXPECT_FALSE(renderer.tracer().last().timed);
    }
    // llvmpipe's workaround (trace-in-draw, forced on here): Auto walks in the draw, untimed.
    const WorkaroundsSet inDraw("trace-in-draw=1");
    SurfaceRenderer renderer;
    for (int draw = 0; draw < 3; ++draw) {
        renderer.draw(plane, glm::mat4(1.0f), surface.textures(), material, camera, light,
                      {.technique = Technique::Hierarchical});
        EXPECT_FALSE(renderer.tracer().last().computeTrace);
        EXPECT_FALSE(renderer.tracer().last().timed);
    }
    const TracePassTrialReport untried = renderer.tracer().passTrial(plane, false);
    EXPECT_FALSE(untried.decided());
    EXPECT_EQ(untried.inDrawDraws + untried.computeDraws, 0);
}

TEST_F(ExactTracerTest, AutoTriesANewMeshAgainWhereverItLiesAndHoldsTheTrialsOfTheMeshesDrawnLast) {
    // A trial is a mesh's (Mesh::uid), not an address's: a mesh made where a freed one was
    // starts its own trial (keyed by address, it took the freed one's decision, untimed). And
    // the trials held are those of the kTrials meshes drawn last (an engine that makes meshes as
    // it goes would otherwise grow them without end): a mesh drawn again after kTrials others is
    // tried again from its first turn, the compute pass; one drawn within them goes on to its
    // second, the draw.
    constexpr int N = 32;
    StaticField field(cl(), N, N, EdgeMode::Wrap, sumOfSines(N, {{0.3, 2, 1, 0.0}}));
    SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    surface.run(field.buffer());
    const SurfaceMaterial material{.depthScale = 0.1f, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.7f, 0.45f, 0.3f}};
    RenderTarget target(32, 18, true);
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 1.6f, 0.3f, 1.2f);
    camera.aspect = 32.0f / 18.0f;
    const WorkaroundsSet set("trace-in-draw=0,cpu-clock-timer=1");
    SurfaceRenderer renderer;
    const auto draw = [&](const Mesh& mesh) {
        target.bind();
        renderer.draw(mesh, glm::mat4(1.0f), surface.textures(), material, camera, light,
                      {.technique = Technique::Hierarchical});
        return std::pair{renderer.tracer().last().computeTrace, renderer.tracer().last().timed};
    };
    const MeshData planeData = makePlane({.size = 2.0f});

    std::optional<Mesh> mesh(std::in_place, planeData);
    const Mesh* const where = &*mesh;
    for (int i = 0; i < 2 * (TracePassTrial::kWarmUp + TracePassTrial::kCounted); ++i) draw(*mesh);
    ASSERT_TRUE(renderer.tracer().passTrial(*mesh, false).decided());
    mesh.emplace(planeData);
    ASSERT_EQ(&*mesh, where);
    EXPECT_FALSE(renderer.tracer().passTrial(*mesh, false).decided()) << "a new mesh where the old one was";
    EXPECT_EQ(draw(*mesh), std::pair(true, true)) << "its first draw: the trial's first turn";

    // The first mesh, drawn once; then others, each drawn once; then the first and the last again.
    const Mesh first(planeData);
    EXPECT_EQ(draw(first), std::pair(true, true));
    std::optional<Mesh> last;
    for (size_t i = 0; i < ExactTracer::kTrials; ++i) {
        last.emplace(planeData);
        ASSERT_EQ(draw(*last), std::pair(true, true)) << "mesh " << i;
    }
    EXPECT_EQ(draw(*last), std::pair(false, true)) << "the last mesh's second turn: its trial is held";
    EXPECT_EQ(draw(first), std::pair(true, true)) << "the first mesh's trial was let go: its first turn again";
}

} // namespace
} // namespace hfx::test
