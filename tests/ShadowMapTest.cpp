// The shadow-map pass against known occluders, seen from straight above: a flat board above a
// relief whose floor lies the full depth under its polygon casts its edge where the light meets
// the floor (the receiver's traced depth), not the polygon; and a relief plateau next to a pit
// shadows a flat board inside the pit only where the traced relief stands between it and the
// light (a caster writing its polygon's depth would darken all of the board: the board lies
// under that polygon).

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GlObject.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/ShadowCascades.h"
#include "hfx/effects/ShadowMap.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/tools/AccuracyProbe.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_precision.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace hfx::test {
namespace {

constexpr int kField = 256, kImage = 256;
constexpr float kPlane = 2.0f, kDepthScale = 0.1f; // the floor: depthScale * plane = 0.2 world units down
constexpr float kFloor = -kDepthScale * kPlane;

class ShadowMaps : public DeviceTest {
protected:
    /// Light from -X, 45 degrees off the plane's normal (+Y); no ambient, so shadow is black.
    DirectionalLight light() const {
        DirectionalLight l;
        l.direction = {-std::sqrt(0.5f), std::sqrt(0.5f), 0.0f};
        l.color = glm::vec3(1.0f);
        l.ambient = glm::vec3(0.0f);
        return l;
    }

    /// One frame as a scene draws it: the relief plane and the board cast into a 1024² map fitted
    /// around the origin; the plane is drawn under the light with that map, and the board too
    /// where `showBoard`. Returns the map's world units per texel.
    float drawWithShadowMap(RenderTarget& target, const AccuracyProbe& probe, const Mesh& board,
                            const glm::mat4& boardModel, Technique technique, bool showBoard) {
        const Mesh plane(makePlane({.size = kPlane}));
        const SurfaceMaterial material{.depthScale = kDepthScale, .lodThreshold = 100.0f};
        SurfaceRenderer renderer;
        ShadowMap map(1024);
        DirectionalLight sun = light();
        map.fit(sun.direction, {0.0f, 0.0f, 0.0f}, 1.6f);
        map.begin();
        renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, map, {.technique = technique});
        renderer.drawFlatShadow(board, boardModel, map);
        map.end();
        sun.shadowMap = &map;
        target.bind();
        target.clear();
        renderer.draw(plane, glm::mat4(1.0f), probe.textures(), material, camera(), sun, {.technique = technique});
        if (showBoard) renderer.drawFlat(board, boardModel, camera(), {1.0f, 1.0f, 1.0f, 1.0f}, &sun);
        return map.texelWorld();
    }
    static Camera camera() { return accuracyCamera(0.0, 8.0f); }

    /// Grey level of every pixel whose ray meets the plane y = receiverY at x in [x0, x1] and
    /// |z| < 0.5, as (world x, brightness) pairs.
    std::vector<std::pair<double, double>> profile(const RenderTarget& target, const Camera& camera, double receiverY,
                                                   double x0, double x1) {
        const Image image = target.readColor();
        std::vector<std::pair<double, double>> out;
        for (int y = 0; y < kImage; ++y)
            for (int x = 0; x < kImage; ++x) {
                const Ray ray = camera.rayThroughPixel(x + 0.5, y + 0.5, kImage, kImage);
                const double t = (receiverY - ray.origin.y) / ray.direction.y;
                const glm::dvec3 p = ray.origin + t * ray.direction;
                if (p.x < x0 || p.x > x1 || std::abs(p.z) > 0.5) continue;
                out.emplace_back(p.x, image.at(x, kImage - 1 - y, 1));
            }
        return out;
    }

    /// Counts pixels of the profile that are lit (> 0.2) where x < edge - margin or dark (< 0.05)
    /// where x > edge + margin; prints the first few.
    static int misplaced(const std::vector<std::pair<double, double>>& profile, double edge, double margin,
                         const char* what) {
        int wrong = 0, dark = 0, lit = 0;
        for (const auto& [x, grey] : profile) {
            if (x < edge - margin) {
                ++dark;
                wrong += grey > 0.2;
            } else if (x > edge + margin) {
                ++lit;
                wrong += grey < 0.05;
            }
        }
        std::printf("[%s] edge at x = %.3f: %d shadowed and %d lit pixels checked, %d misplaced\n", what, edge, dark, lit,
                    wrong);
        EXPECT_GT(dark, 200) << what;
        EXPECT_GT(lit, 200) << what;
        return wrong;
    }
};

TEST_F(ShadowMaps, ABoardAboveTheReliefShadowsItsTracedFloor) {
    // A flat floor the full depth down (h = 0 everywhere); a board at y = 0.3 over x in [-1, 0].
    // Towards the light (-x, +y at 45 degrees) a floor point at x sees the board's edge when
    // x < (0.3 - y) * tan 45: at x = 0.5 on the floor, where the polygon (y = 0) would put it at 0.3.
    AccuracyProbe probe(cl(), std::vector<float>(size_t(kField) * kField, 0.0f), kField, kDepthScale);
    const Mesh board(makePlane({.size = 1.0f}));
    const glm::mat4 boardModel = glm::translate(glm::mat4(1.0f), {-0.5f, 0.3f, 0.0f});
    for (Technique technique : {Technique::ParallaxOcclusion, Technique::Hierarchical}) {
        RenderTarget target(kImage, kImage);
        const float mapTexel = drawWithShadowMap(target, probe, board, boardModel, technique, false);
        // Margin: two map texels and two pixels' worth of world (a pixel is about 0.011 here).
        const double margin = 2.0 * mapTexel + 0.025;
        const auto floor = profile(target, camera(), kFloor, 0.02, 0.98);
        EXPECT_EQ(misplaced(floor, 0.3 - kFloor, margin, techniqueName(technique)), 0);
        // Between the polygon's edge and the floor's, the floor is in shadow: the edge has moved.
        int betweenLit = 0, between = 0;
        for (const auto& [x, grey] : floor)
            if (x > 0.3 + margin && x < 0.3 - kFloor - margin) {
                ++between;
                betweenLit += grey > 0.2;
            }
        EXPECT_GT(between, 500);
        EXPECT_EQ(betweenLit, 0) << techniqueName(technique);
    }
}

TEST_F(ShadowMaps, TheTracedReliefShadowsABoardInItsPit) {
    // A plateau at the polygon (h = 1) for x < 0, a pit the full depth down (h = 0) for x > 0; a
    // board half-way down the pit (y = -0.1) over x in [0, 1]. The plateau's wall, from y = 0
    // down, shades a board point at x when x < 0.1 * tan 45: only the first 0.1 of the board.
    std::vector<float> heights(size_t(kField) * kField);
    for (int v = 0; v < kField; ++v)
        for (int u = 0; u < kField; ++u) heights[size_t(v) * kField + u] = u < kField / 2 ? 1.0f : 0.0f;
    AccuracyProbe probe(cl(), heights, kField, kDepthScale);
    const Mesh board(makePlane({.size = 1.0f}));
    const glm::mat4 boardModel = glm::translate(glm::mat4(1.0f), {0.5f, -0.1f, 0.0f});
    for (Technique technique : {Technique::ParallaxOcclusion, Technique::Hierarchical}) {
        RenderTarget target(kImage, kImage);
        const float mapTexel = drawWithShadowMap(target, probe, board, boardModel, technique, true);
        // The wall's foot spreads over one field texel (bilinear): margin two map texels, one
        // field texel and two pixels.
        const double margin = 2.0 * mapTexel + kPlane / kField + 0.025;
        const auto boardProfile = profile(target, camera(), -0.1, 0.02, 0.98);
        EXPECT_EQ(misplaced(boardProfile, 0.1, margin, techniqueName(technique)), 0);
    }
}

TEST_F(ShadowMaps, ACastersWalksInAComputePassWriteTheDepthsTheDrawWrites) {
    // TracePass::Compute for a shadow caster (trace/hier/trace.glsl): the rays draw stores each map
    // texel's light ray, the pass walks it, and the draw writes the hit's depth. The map must hold
    // the depths the draw that walks writes: where a board in front hides part of the relief (the
    // rays draw leaves those texels to it), for a plane and a sphere (a back face stores nothing),
    // with the light at two angles. A draw that read no slot, or another texel's, writes the
    // polygon's depth or another texel's hit. Measured on llvmpipe: the maps are the same to the
    // bit (the sphere's back faces culled: before they were, 8 and 3 texels on its silhouette
    // differed). On a GPU the plane's rays are the rasteriser's rounding in the draw and the
    // screen map's in the pass (no rays draw on a flat patch), and the blocks' walls carry it into
    // the depth (the H200: 16123 of 72044 texels more than 1e-6 apart, 0.036 at most): a texel
    // counts as apart past 1e-4 of the map's depth (the relief spans about 0.03 of it).
    const AccuracyProbe probe(cl(), blocks(kField, 8), kField, kDepthScale);
    const Mesh plane(makePlane({.size = kPlane})), sphere(makeSphere({.radius = 0.8f}));
    const Mesh board(makePlane({.size = 0.5f}));
    const glm::mat4 boardModel = glm::translate(glm::mat4(1.0f), {0.3f, 0.4f, 0.1f});
    const SurfaceMaterial material{.depthScale = kDepthScale, .lodThreshold = 100.0f};
    constexpr int kMap = 512;
    for (const Mesh* mesh : {&plane, &sphere})
        for (const glm::vec3 towards : {glm::vec3(-0.7f, 0.7f, 0.1f), glm::vec3(0.3f, 0.9f, -0.4f)}) {
            const std::string what = str(mesh == &plane ? "plane" : "sphere", ", light ", towards.x, " ", towards.y);
            SCOPED_TRACE(what);
            SurfaceRenderer renderer;
            ShadowMap map(kMap);
            map.fit(towards, {0.0f, 0.0f, 0.0f}, 1.6f);
            auto cast = [&](TracePass pass) {
                {
                    const auto casting = map.scope();
                    renderer.drawFlatShadow(board, boardModel, map);
                    renderer.drawShadow(*mesh, glm::mat4(1.0f), probe.textures(), material, map,
                                        {.technique = Technique::Hierarchical, .tracePass = pass});
                }
                EXPECT_EQ(renderer.tracer().lastCaster().computeTrace, pass == TracePass::Compute);
                std::vector<float> depth(size_t(kMap) * kMap);
                glGetTextureImage(map.texture(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(depth.size() * sizeof(float)),
                                  depth.data());
                return depth;
            };
            const std::vector<float> walked = cast(TracePass::InDraw), computed = cast(TracePass::Compute);
            size_t relief = 0, differ = 0, rounded = 0;
            double largest = 0.0;
            for (size_t i = 0; i < walked.size(); ++i) {
                relief += walked[i] < 1.0f;
                const double d = std::abs(double(walked[i]) - double(computed[i]));
                differ += d > 1e-4;
                rounded += d > 1e-6;
                largest = std::max(largest, d);
            }
            std::printf("[caster's computed walks] %s: %zu of %zu map texels hold a depth, %zu differ by more than 1e-4 "
                        "(%zu by more than 1e-6, largest %.2g)\n",
                        what.c_str(), relief, walked.size(), differ, rounded, largest);
            EXPECT_GT(relief, walked.size() / 8) << "too little cast to tell";
            EXPECT_LE(differ, relief / 2000);
        }
}

/// As an engine begins a light's tile (x0, 0, size, size) of the bound framebuffer: its viewport,
/// the clip control of the light's depth convention, its depth cleared to the far plane.
void beginLightTile(int x0, int size, bool reversedZ) {
    glViewport(x0, 0, size, size);
    glClipControl(GL_LOWER_LEFT, reversedZ ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, 0, size, size);
    glClearDepthf(reversedZ ? 0.0f : 1.0f);
    glClear(GL_DEPTH_BUFFER_BIT);
    glClearDepthf(1.0f);
    glDisable(GL_SCISSOR_TEST);
}

/// An engine's own shadow atlas: a 32-bit float depth texture and an RGBA8 colour attachment (a
/// map of moments, a debug view), lights drawn into tiles of it through viewports.
struct EngineShadowAtlas {
    // Whole bytes: GL lets a device convert a value between two bytes to either (it should take
    // the nearer), and 0.5 is 127.5, a tie, which llvmpipe makes 128. On an H200 every one of
    // the atlas's 51200 texels differed from the colour this test expected, which a 127 there
    // would explain.
    static constexpr glm::u8vec4 kBytes{64, 128, 191, 255};
    static constexpr glm::vec4 kColour = glm::vec4(kBytes) / 255.0f;
    EngineShadowAtlas(int w, int h)
        : width(w), height(h), fbo(GlFramebuffer::create()), depth(GlTexture::create()), colour(GlTexture::create()) {
        glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
        glTextureStorage2D(colour.id(), 1, GL_RGBA8, width, height);
        glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
        glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, &kColour.x);
    }
    /// Binds the atlas with the tile (x0, 0, size, size) for a light's casters (beginLightTile).
    void beginTile(int x0, int size, bool reversedZ) const {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        beginLightTile(x0, size, reversedZ);
    }
    static void endTile() { glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE); }
    std::vector<float> depths() const {
        std::vector<float> d(size_t(width) * height);
        glGetTextureImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(d.size() * sizeof(float)), d.data());
        return d;
    }
    std::vector<glm::u8vec4> colours() const {
        std::vector<glm::u8vec4> c(size_t(width) * height);
        glGetTextureImage(colour.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(c.size() * 4), c.data());
        return c;
    }
    int width, height;
    GlFramebuffer fbo;
    GlTexture depth, colour;
};

// An engine's own shadow maps (a spot light's perspective view in one tile of its atlas, a sun's
// cascade, orthographic and reversed-Z, in the next): each texel holds the depth of the first
// thing its light ray meets, the traced relief's or a board's above it, as the CPU finds it
// (HeightFieldTracer's exact hit along the texel's ray, the board's plane), in the light's depth
// convention; the engine's colour attachment keeps its colour. A caster tracing the light's
// direction for every texel (a ShadowMap's parallel rays) puts the spot light's relief elsewhere;
// one writing its polygon's depth is off on most texels.
TEST_F(ShadowMaps, AnEnginesOwnMapsHoldTheTracedReliefAlongEachLightsRays) {
    constexpr int kSines = 64, kTile = 160;
    constexpr float depthScale = 0.15f, boardY = 0.3f;
    const std::vector<float> heights = sumOfSines(kSines, {{0.3, 2, 1, 0.0}, {0.15, -1, 2, 0.7}});
    const AccuracyProbe probe(cl(), heights, kSines, depthScale);
    const HeightFieldTracer exact(heights, kSines, kSines, EdgeMode::Wrap);
    const Mesh plane(makePlane({.size = kPlane}));
    const Mesh board(makePlane({.size = 0.5f}));
    const glm::mat4 boardModel = glm::translate(glm::mat4(1.0f), {-0.3f, boardY, 0.2f});
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f};
    const glm::vec3 sunward = glm::normalize(glm::vec3(-0.5f, 0.8f, 0.3f)), centre(0.2f, 0.0f, -0.1f);
    const struct {
        const char* name;
        Camera view;
    } lights[] = {
        {"spot light", Camera::fromMatrices(glm::lookAt(glm::vec3(0.9f, 1.4f, 0.7f), glm::vec3(0.0f), glm::vec3(0, 1, 0)),
                                            glm::perspective(glm::radians(70.0f), 1.0f, 0.3f, 6.0f))},
        {"sun's cascade, reversed Z",
         Camera::fromMatrices(glm::lookAt(centre + 3.0f * sunward, centre, glm::vec3(0, 1, 0)),
                              glm::orthoRH_ZO(-0.8f, 0.8f, -0.8f, 0.8f, 5.0f, 1.0f), true)}};
    EngineShadowAtlas atlas(2 * kTile, kTile);
    const auto recoloured = [&] {
        size_t count = 0;
        for (const glm::u8vec4& c : atlas.colours()) count += c != EngineShadowAtlas::kBytes;
        return count;
    };
    ASSERT_EQ(recoloured(), 0u) << "the atlas's own clear did not take";
    for (const TracePass pass : {TracePass::InDraw, TracePass::Compute}) {
        SurfaceRenderer renderer;
        for (int tile = 0; tile < 2; ++tile) {
            const Camera& light = lights[tile].view;
            atlas.beginTile(tile * kTile, kTile, light.reversedZ);
            renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, light,
                                {.technique = Technique::Hierarchical, .tracePass = pass});
            EXPECT_EQ(renderer.tracer().lastCaster().computeTrace, pass == TracePass::Compute);
            renderer.drawFlatShadow(board, boardModel, light);
            EngineShadowAtlas::endTile();
        }
        EXPECT_EQ(recoloured(), 0u) << "the casters wrote the engine's colour attachment, "
                                    << (pass == TracePass::Compute ? "walking in a compute pass" : "walking in the draw");
        const std::vector<float> depth = atlas.depths();
        for (int tile = 0; tile < 2; ++tile) {
            const Camera& light = lights[tile].view;
            const std::string what = str(lights[tile].name, pass == TracePass::Compute ? ", a compute pass" : ", the draw");
            SCOPED_TRACE(what);
            const glm::dmat4 viewProj(light.viewProjection());
            const auto windowDepth = [&](const glm::dvec3& p) {
                const glm::dvec4 clip = viewProj * glm::dvec4(p, 1.0);
                return light.reversedZ ? clip.z / clip.w : 0.5 * clip.z / clip.w + 0.5;
            };
            size_t relief = 0, boards = 0, off = 0, polygonOff = 0;
            double worst = 0.0;
            for (int y = 0; y < kTile; ++y)
                for (int x = 0; x < kTile; ++x) {
                    const Ray ray = light.rayThroughPixel(x + 0.5, y + 0.5, kTile, kTile);
                    // The board's plane, over its square; then the relief under the plane's polygon.
                    const double tBoard = (boardY - ray.origin.y) / ray.direction.y;
                    const glm::dvec3 b = ray.origin + tBoard * ray.direction;
                    const bool onBoard = tBoard > 0.0 && std::abs(b.x + 0.3) < 0.25 && std::abs(b.z - 0.2) < 0.25;
                    glm::dvec2 uv0;
                    glm::dvec3 toLight;
                    const bool onPlane = planePixelRay(light, kPlane, x, y, kTile, kTile, uv0, toLight);
                    const auto hit = onPlane ? exact.traceView(uv0, toLight, depthScale) : std::nullopt;
                    if (!onBoard && !hit) continue;
                    // (A texel whose centre lies within a thousandth of the board's edge is the
                    // rasteriser's rounding.)
                    if (std::abs(std::abs(b.x + 0.3) - 0.25) < 1e-3 || std::abs(std::abs(b.z - 0.2) - 0.25) < 1e-3) continue;
                    const glm::dvec3 p = onBoard ? b
                                                 : glm::dvec3((hit->uv.x - 0.5) * kPlane,
                                                              -(1.0 - hit->height) * depthScale * kPlane,
                                                              (0.5 - hit->uv.y) * kPlane);
                    const double expected = windowDepth(p);
                    const double error = std::abs(expected - depth[size_t(y) * atlas.width + tile * kTile + x]);
                    (onBoard ? boards : relief) += 1;
                    worst = std::max(worst, error);
                    off += error > 1e-5;
                    if (!onBoard) {
                        const glm::dvec3 polygon((uv0.x - 0.5) * kPlane, 0.0, (0.5 - uv0.y) * kPlane);
                        polygonOff += std::abs(windowDepth(polygon) - expected) > 1e-5;
                    }
                }
            std::printf("[engine's shadow map] %s: %zu relief and %zu board texels, %zu off the exact depth by more "
                        "than 1e-5 (%.2g at most); the polygon's depth would be off on %zu\n",
                        what.c_str(), relief, boards, off, worst, polygonOff);
            EXPECT_GT(relief, size_t(kTile * kTile / 3));
            EXPECT_GT(boards, size_t(kTile * kTile / 50));
            EXPECT_GT(polygonOff, relief * 9 / 10);
            EXPECT_LE(off, (relief + boards) / 500);
        }
    }
}

/// An engine's cascade of a directional light: an orthographic view of the sphere (centre,
/// radius) from `towards`, its near plane pulled `reach` towards the light (the casters outside
/// the sphere that shade it), with the depth convention asked for.
Camera cascadeView(glm::vec3 towards, glm::vec3 centre, float radius, float reach, bool reversedZ) {
    const glm::mat4 view = glm::lookAt(centre + towards * (radius + reach), centre, glm::vec3(0.0f, 0.0f, 1.0f));
    const float depth = 2.0f * radius + reach;
    const glm::mat4 projection = reversedZ ? glm::orthoRH_ZO(-radius, radius, -radius, radius, depth, 0.0f)
                                           : glm::ortho(-radius, radius, -radius, radius, 0.0f, depth);
    return Camera::fromMatrices(view, projection, reversedZ);
}

/// An engine's depth texture for its cascades: an atlas (GL_TEXTURE_2D, `tiles` side by side) or
/// an array (one layer each).
struct EngineCascadeTexture {
    EngineCascadeTexture(bool isArray, int count, int edge) : array(isArray), tiles(count), size(edge), fbo(GlFramebuffer::create()) {
        if (array) {
            layers = GlTextureArray::create();
            glTextureStorage3D(layers.id(), 1, GL_DEPTH_COMPONENT32F, size, size, tiles);
        } else {
            atlas = GlTexture::create();
            glTextureStorage2D(atlas.id(), 1, GL_DEPTH_COMPONENT32F, size * tiles, size);
        }
        texture = array ? layers.id() : atlas.id();
        glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
        glNamedFramebufferReadBuffer(fbo.id(), GL_NONE);
    }
    /// Binds cascade i's tile or layer for its casters, cleared to its far plane.
    void begin(int i, bool reversedZ) const {
        if (array)
            glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, texture, 0, i);
        else
            glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, texture, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        beginLightTile(array ? 0 : i * size, size, reversedZ);
    }
    ShadowCascade cascade(int i, const Camera& view) const {
        return {.viewProj = view.viewProjection(),
                .tile = array ? glm::vec4(0.0f, 0.0f, 1.0f, 1.0f) : glm::vec4(float(i) / float(tiles), 0.0f, 1.0f / float(tiles), 1.0f),
                .layer = array ? i : 0};
    }
    bool array;
    int tiles, size;
    GlTexture atlas;
    GlTextureArray layers;
    GLuint texture = 0; ///< the one of the two in use
    GlFramebuffer fbo;
};

// The relief receiving an engine's own cascades of the sun (DirectionalLight::cascades), as it
// receives a ShadowMap: a board above a floor the full depth down shades the floor up to where
// the light meets it (x = 0.5, not the polygon's 0.3), in an atlas of two tiles with reversed Z
// and in an array of two layers with GL's default. The finer cascade holds only the floor around
// the edge, the coarser everything; the finer is read wherever it holds a point (left empty, the
// shadow it holds goes), and its tile is where it lies in the texture.
TEST_F(ShadowMaps, AnEnginesCascadesShadowTheReliefAsAShadowMapDoes) {
    AccuracyProbe probe(cl(), std::vector<float>(size_t(kField) * kField, 0.0f), kField, kDepthScale);
    const Mesh plane(makePlane({.size = kPlane}));
    const Mesh board(makePlane({.size = 1.0f}));
    const glm::mat4 boardModel = glm::translate(glm::mat4(1.0f), {-0.5f, 0.3f, 0.0f});
    const SurfaceMaterial material{.depthScale = kDepthScale, .lodThreshold = 100.0f};
    const DirectionalLight sun = light();
    constexpr int kCascade = 1024;
    for (const bool array : {false, true}) {
        const bool reversedZ = !array;
        const Camera views[2] = {cascadeView(sun.direction, {0.45f, -0.1f, 0.0f}, 0.45f, 1.5f, reversedZ),
                                 cascadeView(sun.direction, {0.0f, 0.0f, 0.0f}, 1.6f, 0.0f, reversedZ)};
        for (const bool fineEmpty : {false, true}) {
            const std::string what = str(array ? "an array" : "an atlas, reversed Z", fineEmpty ? ", the finer cascade empty" : "");
            SCOPED_TRACE(what);
            SurfaceRenderer renderer;
            const EngineCascadeTexture maps(array, 2, kCascade);
            ShadowCascade cascades[2];
            for (int i = 0; i < 2; ++i) {
                maps.begin(i, reversedZ);
                if (!(fineEmpty && i == 0)) {
                    renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, views[i],
                                        {.technique = Technique::Hierarchical});
                    renderer.drawFlatShadow(board, boardModel, views[i]);
                }
                cascades[i] = maps.cascade(i, views[i]);
            }
            glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
            const ShadowCascades engine{.texture = maps.texture, .reversedZ = reversedZ, .cascades = cascades};
            DirectionalLight received = sun;
            received.cascades = &engine;
            RenderTarget target(kImage, kImage);
            target.bind();
            target.clear();
            // The engine's own sampler and array texture on the unit: what the draw puts back.
            const GlSampler engineSampler = GlSampler::create();
            glBindSampler(HFX_UNIT_SHADOW_MAP, engineSampler.id());
            const GlTextureArray engineArray = GlTextureArray::create();
            glTextureStorage3D(engineArray.id(), 1, GL_RGBA8, 1, 1, 1);
            glBindTextureUnit(HFX_UNIT_SHADOW_MAP, engineArray.id());
            renderer.draw(plane, glm::mat4(1.0f), probe.textures(), material, camera(), received,
                          {.technique = Technique::Hierarchical});
            GLint sampler = 0, arrayBound = -1;
            glActiveTexture(GL_TEXTURE0 + HFX_UNIT_SHADOW_MAP);
            glGetIntegerv(GL_SAMPLER_BINDING, &sampler);
            glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &arrayBound);
            glActiveTexture(GL_TEXTURE0);
            glBindSampler(HFX_UNIT_SHADOW_MAP, 0);
            glBindTextureUnit(HFX_UNIT_SHADOW_MAP, 0);
            EXPECT_EQ(GLuint(sampler), engineSampler.id());
            EXPECT_EQ(GLuint(arrayBound), engineArray.id());
            // The coarser cascade's texel and two pixels' worth of world.
            const double margin = 2.0 * (2.0 * 1.6 / kCascade) + 0.025;
            const auto floor = profile(target, camera(), kFloor, 0.02, 0.98);
            const int wrong = misplaced(floor, 0.3 - kFloor, margin, what.c_str());
            if (fineEmpty)
                EXPECT_GT(wrong, 100) << "the finer cascade is read where it holds the point";
            else
                EXPECT_EQ(wrong, 0);
        }
    }
}

TEST_F(ShadowMaps, ABadCascadeIsRefusedByNameBeforeAnythingIsDrawn) {
    AccuracyProbe probe(cl(), sumOfSines(64, {{0.4, 2, 1, 0.0}}), 64, kDepthScale);
    const Mesh plane(makePlane({.size = kPlane}));
    const SurfaceMaterial material{.depthScale = kDepthScale};
    SurfaceRenderer renderer;
    const EngineCascadeTexture maps(false, 2, 64);
    GlTexture colour = GlTexture::create();
    glTextureStorage2D(colour.id(), 1, GL_RGBA8, 64, 64);
    const Camera view = cascadeView(light().direction, {0.0f, 0.0f, 0.0f}, 1.6f, 0.0f, false);
    const ShadowCascade good = maps.cascade(0, view);
    RenderTarget target(32, 32);
    target.bind();
    const auto refusal = [&](const ShadowCascades& cascades, const ShadowMap* map = nullptr) {
        target.clear({0.0f, 0.0f, 1.0f, 1.0f});
        DirectionalLight sun = light();
        sun.cascades = &cascades;
        sun.shadowMap = map;
        const std::string message = messageOf([&] {
            renderer.draw(plane, glm::mat4(1.0f), probe.textures(), material, accuracyCamera(0.0, 4.0f), sun);
        });
        const Image image = target.readColor();
        EXPECT_EQ(image.at(16, 16, 2), 1.0f) << "drawn before the refusal: " << message;
        return message;
    };
    const auto with = [&](auto change) {
        ShadowCascade c = good;
        change(c);
        return c;
    };
    const ShadowCascade five[5] = {good, good, good, good, good};
    const ShadowCascade perspective = with([](ShadowCascade& c) { c.viewProj = glm::perspective(1.0f, 1.0f, 0.1f, 10.0f); });
    const ShadowCascade notFinite = with([](ShadowCascade& c) { c.viewProj[1][1] = std::nanf(""); });
    const ShadowCascade outside = with([](ShadowCascade& c) { c.tile = {0.75f, 0.0f, 0.5f, 1.0f}; });
    const ShadowCascade layered = with([](ShadowCascade& c) { c.layer = 1; });
    EXPECT_NE(refusal({.texture = maps.texture}).find("1 to 4 cascades, got 0"), std::string::npos);
    EXPECT_NE(refusal({.texture = maps.texture, .cascades = five}).find("1 to 4 cascades, got 5"), std::string::npos);
    EXPECT_NE(refusal({.texture = 0, .cascades = std::span(&good, 1)}).find("texture 0 is not a GL texture"), std::string::npos);
    EXPECT_NE(refusal({.texture = colour.id(), .cascades = std::span(&good, 1)}).find("must hold depth"), std::string::npos);
    EXPECT_NE(refusal({.texture = maps.texture, .cascades = std::span(&perspective, 1)}).find("orthographic"), std::string::npos);
    EXPECT_NE(refusal({.texture = maps.texture, .cascades = std::span(&notFinite, 1)}).find("cascade 0's viewProj is not finite"),
              std::string::npos);
    EXPECT_NE(refusal({.texture = maps.texture, .cascades = std::span(&outside, 1)}).find("tile must lie in the texture"),
              std::string::npos);
    EXPECT_NE(refusal({.texture = maps.texture, .cascades = std::span(&layered, 1)}).find("layer 1 is outside"), std::string::npos);
    ShadowMap map(64);
    DirectionalLight unfitted = light();
    unfitted.shadowMap = &map;
    target.clear({0.0f, 0.0f, 1.0f, 1.0f});
    EXPECT_NE(messageOf([&] {
                  renderer.draw(plane, glm::mat4(1.0f), probe.textures(), material, accuracyCamera(0.0, 4.0f), unfitted);
              }).find("DirectionalLight.shadowMap has no light's view yet"),
              std::string::npos);
    EXPECT_EQ(target.readColor().at(16, 16, 2), 1.0f) << "drawn under a map that was never fitted";
    map.fit(light().direction, {0.0f, 0.0f, 0.0f}, 1.6f);
    EXPECT_NE(refusal({.texture = maps.texture, .cascades = std::span(&good, 1)}, &map).find("its shadowMap or its cascades, not both"),
              std::string::npos);
}

TEST_F(ShadowMaps, CastersOutsideAMapsPassOrUnderAnotherDepthConventionAreRefusedByName) {
    AccuracyProbe probe(cl(), sumOfSines(64, {{0.4, 2, 1, 0.0}}), 64, kDepthScale);
    const Mesh plane(makePlane({.size = kPlane}));
    const SurfaceMaterial material{.depthScale = kDepthScale};
    SurfaceRenderer renderer;
    ShadowMap map(64);
    const auto cast = [&] { renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, map); };
    const auto flat = [&] { renderer.drawFlatShadow(plane, glm::mat4(1.0f), map); };
    EXPECT_NE(messageOf(cast).find("no light's view yet (ShadowMap::fit)"), std::string::npos);
    map.fit(light().direction, {0.0f, 0.0f, 0.0f}, 1.6f);
    EXPECT_NE(messageOf(cast).find("the shadow map is not begun"), std::string::npos);
    EXPECT_NE(messageOf(flat).find("drawFlatShadow: the shadow map is not begun"), std::string::npos);
    {
        const auto casting = map.scope();
        cast();
        flat();
    }
    // An engine's reversed-Z light view drawn under GL's default clip depth, and the other way.
    RenderTarget target(32, 32);
    target.bind();
    const Camera reversed = Camera::fromMatrices(glm::lookAt(glm::vec3(0, 3, 0), glm::vec3(0), glm::vec3(0, 0, 1)),
                                                 glm::orthoRH_ZO(-1.5f, 1.5f, -1.5f, 1.5f, 5.0f, 1.0f), true);
    EXPECT_NE(messageOf([&] { renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, reversed); })
                  .find("the camera is reversed-Z"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { renderer.drawFlatShadow(plane, glm::mat4(1.0f), reversed); }).find("the camera is reversed-Z"),
              std::string::npos);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    EXPECT_NE(messageOf([&] { renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, map.lightView()); })
                  .find("GL_ZERO_TO_ONE"),
              std::string::npos);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    // A light view that is no camera: its projection not invertible.
    Camera broken = reversed;
    broken.customProjection = glm::mat4(0.0f);
    EXPECT_NE(messageOf([&] { renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, broken); })
                  .find("projection"),
              std::string::npos);
}

TEST_F(ShadowMaps, BadFitsAndSizesAreRefusedByName) {
    EXPECT_NE(messageOf([] { ShadowMap m(8); }).find("16..16384"), std::string::npos);
    ShadowMap map(64);
    EXPECT_NE(messageOf([&] { map.fit({0, 0, 0}, {0, 0, 0}, 1.0f); }).find("direction"), std::string::npos);
    EXPECT_NE(messageOf([&] { map.fit({0, 1, 0}, {0, std::nanf(""), 0}, 1.0f); }).find("the centre must be finite, got (0, nan, 0)"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { map.fit({0, 1, 0}, {0, 0, 0}, -1.0f); }).find("radius"), std::string::npos);
}

TEST_F(ShadowMaps, APassPutsBackTheFramebuffersAndViewportItFound) {
    RenderTarget drawn(64, 48), read(32, 32);
    drawn.bind();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read.framebuffer());
    ShadowMap map(128);
    map.begin();
    GLint draw = 0, viewport[4] = {};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_NE(GLuint(draw), drawn.framebuffer());
    EXPECT_EQ(viewport[2], 128);
    map.end();
    GLint readBack = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readBack);
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(GLuint(draw), drawn.framebuffer());
    EXPECT_EQ(GLuint(readBack), read.framebuffer());
    EXPECT_EQ(viewport[2], 64);
    EXPECT_EQ(viewport[3], 48);
}

TEST_F(ShadowMaps, ACallersScissorAndDepthMaskNeitherSpoilTheMapNorOutliveItsPass) {
    // A caller may leave a scissor around one pixel and depth writes off (a transparent pass, a
    // UI): the map must still be cleared and cast in full, and get them back at end().
    AccuracyProbe probe(cl(), sumOfSines(64, {{0.4, 2, 1, 0.0}}), 64, kDepthScale);
    const Mesh plane(makePlane({.size = kPlane}));
    const SurfaceMaterial material{.depthScale = kDepthScale};
    SurfaceRenderer renderer;
    const auto depths = [&](bool spoiled) {
        ShadowMap map(64);
        map.fit(light().direction, {0.0f, 0.0f, 0.0f}, 1.6f);
        if (spoiled) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, 0, 1, 1);
            glDepthMask(GL_FALSE);
        }
        {
            const auto casting = map.scope();
            renderer.drawShadow(plane, glm::mat4(1.0f), probe.textures(), material, map,
                                {.technique = Technique::Hierarchical, .tracePass = deviceTracePass()});
        }
        if (spoiled) {
            EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
            GLboolean mask = GL_TRUE;
            glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
            EXPECT_FALSE(mask);
            glDisable(GL_SCISSOR_TEST);
            glDepthMask(GL_TRUE);
        }
        std::vector<float> d(64 * 64, -1.0f);
        HFX_GL_CHECK(glGetTextureImage(map.texture(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(d.size() * sizeof(float)),
                                       d.data()));
        return d;
    };
    const std::vector<float> clean = depths(false);
    ASSERT_LT(*std::min_element(clean.begin(), clean.end()), 0.9f) << "the relief must cast into the map";
    EXPECT_EQ(depths(true), clean);
}

TEST_F(ShadowMaps, APassIsBegunOnceAndEndsEvenWhenACasterThrows) {
    ShadowMap map(64);
    map.begin();
    EXPECT_NE(messageOf([&] { map.begin(); }).find("already begun"), std::string::npos);
    map.end();
    EXPECT_NE(messageOf([&] { map.end(); }).find("not begun"), std::string::npos);
    RenderTarget drawn(32, 16);
    drawn.bind();
    EXPECT_THROW(
        {
            const auto casting = map.scope();
            throw Error("a caster failed");
        },
        Error);
    EXPECT_FALSE(map.begun());
    GLint draw = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    EXPECT_EQ(GLuint(draw), drawn.framebuffer());
    map.begin(); // and it can be begun again
    map.end();
}

} // namespace
} // namespace hfx::test
