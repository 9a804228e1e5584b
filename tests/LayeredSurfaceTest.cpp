// Layered surfaces (the ocean's cascades): a layer B of half the texels drawn at twice the scale
// has its texel centres exactly on layer A's, so the two-layer surface wA A + wB B is, texel for
// texel, one surface C on A's grid, and bilinear filtering agrees too. Drawn layered, it must
// trace and shade as C drawn alone, and hit where the exact intersection of C says.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/compute/StaticField.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/tools/AccuracyProbe.h"

#include <glm/geometric.hpp>

namespace hfx::test {
namespace {

class LayeredSurface : public DeviceTest {};

constexpr int N = 64;
constexpr float kWeightA = 0.7f, kWeightB = 0.3f;

struct Layers {
    std::vector<float> a, b, sum;
    std::unique_ptr<StaticField> fieldA, fieldB, fieldSum;
    std::unique_ptr<SurfacePipeline> surfaceA, surfaceB, surfaceSum;
};

/// `relief` scales the waves' amplitudes: at 1 the sum spans most of the depth; the ocean's
/// cascades, whose depth is 8 sigma, keep most of their heights within the middle half.
Layers makeLayers(ClContext& cl, double relief = 1.0) {
    Layers l;
    l.a = sumOfSines(N, {{0.25 * relief, 2, 1, 0.3}, {0.1 * relief, -1, 4, 1.0}});
    l.b = sumOfSines(N / 2, {{0.3 * relief, 1, 2, 0.8}, {0.12 * relief, 3, -2, 0.1}});
    l.sum.resize(size_t(N) * N);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x)
            l.sum[size_t(y) * N + x] = kWeightA * l.a[size_t(y) * N + x] + kWeightB * l.b[size_t(y % (N / 2)) * (N / 2) + x % (N / 2)];
    l.fieldA = std::make_unique<StaticField>(cl, N, N, EdgeMode::Wrap, l.a);
    l.fieldB = std::make_unique<StaticField>(cl, N / 2, N / 2, EdgeMode::Wrap, l.b);
    l.fieldSum = std::make_unique<StaticField>(cl, N, N, EdgeMode::Wrap, l.sum);
    // Each with normals for a depth of its own: the renderer combines their slopes.
    const SurfaceOptions options{.mipmaps = false};
    l.surfaceA = std::make_unique<SurfacePipeline>(cl, SurfacePipelineConfig::of(*l.fieldA, 0.05f, options));
    l.surfaceB = std::make_unique<SurfacePipeline>(cl, SurfacePipelineConfig::of(*l.fieldB, 0.02f, options));
    l.surfaceSum = std::make_unique<SurfacePipeline>(cl, SurfacePipelineConfig::of(*l.fieldSum, 0.08f, {.mipmaps = false}));
    l.surfaceA->run(l.fieldA->buffer());
    l.surfaceB->run(l.fieldB->buffer());
    l.surfaceSum->run(l.fieldSum->buffer());
    return l;
}

constexpr int kImage = 160;

/// Draws layered surfaces on a 2-unit plane seen at 50 degrees, into a kImage^2 target with the
/// trace output: the colour (top row first) and the trace (bottom row first).
struct LayerShot {
    const Mesh plane{makePlane({.size = 2.0f})};
    const Camera camera = accuracyCamera(50.0);
    SurfaceRenderer renderer;
    RenderTarget target{kImage, kImage, true};
    std::pair<Image, std::vector<glm::vec4>> operator()(std::span<const SurfaceLayer> layers,
                                                        const SurfaceMaterial& material, const DirectionalLight& light) {
        target.bind();
        target.clear();
        renderer.draw(plane, glm::mat4(1.0f), layers, material, camera, light, {.traceOutput = true});
        return {target.readColor(), target.readTrace()};
    }
};

TEST_F(LayeredSurface, DrawsAsTheSingleSurfaceOfItsSumAndHitsItsExactIntersection) {
    const Layers l = makeLayers(cl());
    const SurfaceLayer layered[] = {{.textures = &l.surfaceA->textures(), .weight = kWeightA},
                                    {.textures = &l.surfaceB->textures(), .texcoordScale = 2.0f, .weight = kWeightB}};
    const SurfaceMaterial material{.depthScale = 0.1f, .minSamples = 8, .maxSamples = 32, .lodThreshold = 100.0f, .shadows = true};
    DirectionalLight light;
    light.direction = {0.6f, 0.55f, 0.3f};
    LayerShot shot;
    const Camera& camera = shot.camera;
    constexpr int image = kImage;
    const SurfaceLayer single{.textures = &l.surfaceSum->textures()};
    const auto [colorLayered, traceLayered] = shot(layered, material, light);
    const auto [colorSingle, traceSingle] = shot(std::span(&single, 1), material, light);

    // Colour: the slopes summed per layer are the sum's slopes (Sobel is linear), so shading
    // agrees to a rounding step; a search decision flipped by float rounding may move a pixel.
    size_t far = 0;
    for (size_t i = 0; i < colorSingle.pixels.size(); ++i) far += std::abs(colorSingle.pixels[i] - colorLayered.pixels[i]) > 2.5f / 255;
    EXPECT_LT(double(far) / colorSingle.pixels.size(), 0.002) << "of the colour values differ by more than 2 steps";

    // Hits: against the layered draw's twin and against the exact bilinear intersection of C.
    const HeightFieldTracer exact(l.sum, N, N, EdgeMode::Wrap);
    std::vector<double> toTwin, toExact;
    for (int y = 0; y < image; ++y)
        for (int x = 0; x < image; ++x) {
            const glm::vec4 a = traceLayered[size_t(y) * image + x], b = traceSingle[size_t(y) * image + x];
            if (a.w == 0.0f) continue;
            toTwin.push_back(glm::length(glm::vec2(a) - glm::vec2(b)) * N);
            glm::dvec2 uv0;
            glm::dvec3 toEye;
            if (!planePixelRay(camera, 2.0f, x, y, image, image, uv0, toEye)) continue;
            if (const auto hit = exact.traceView(uv0, toEye, material.depthScale))
                toExact.push_back(glm::length(glm::dvec2(a.x, a.y) - hit->uv) * N);
        }
    ASSERT_GT(toExact.size(), 1000u);
    EXPECT_LT(statistics(toTwin).mean, 0.01) << "texels between the layered and the summed surface's hits";
    // POM with 8..32 samples at 50 degrees (docs/ACCURACY.md, smooth map: about 0.003 texel).
    EXPECT_LT(statistics(toExact).mean, 0.05) << "texels from the exact intersection";
}

// An untraced layer stands flat at its rest height in the trace: the hits are the exact
// intersection of wA A + wB rest, not of the sum; the slopes still include it.
TEST_F(LayeredSurface, AnUntracedLayerIsFlatInTheTraceAndStillShades) {
    const Layers l = makeLayers(cl());
    constexpr float rest = 0.3f;
    const SurfaceLayer layered[] = {
        {.textures = &l.surfaceA->textures(), .weight = kWeightA},
        {.textures = &l.surfaceB->textures(), .texcoordScale = 2.0f, .weight = kWeightB, .traced = false, .restHeight = rest}};
    const SurfaceLayer full[] = {{.textures = &l.surfaceA->textures(), .weight = kWeightA},
                                 {.textures = &l.surfaceB->textures(), .texcoordScale = 2.0f, .weight = kWeightB}};
    const SurfaceMaterial material{.depthScale = 0.1f, .minSamples = 8, .maxSamples = 32, .lodThreshold = 100.0f, .shadows = false};
    LayerShot shot;
    const Camera& camera = shot.camera;
    constexpr int image = kImage;
    const auto [colorUntraced, traceUntraced] = shot(layered, material, {});
    const auto [colorFull, traceFull] = shot(full, material, {});

    std::vector<float> flat(size_t(N) * N);
    for (size_t i = 0; i < flat.size(); ++i) flat[i] = kWeightA * l.a[i] + kWeightB * rest;
    const HeightFieldTracer exactFlat(flat, N, N, EdgeMode::Wrap), exactSum(l.sum, N, N, EdgeMode::Wrap);
    std::vector<double> toFlat, toSum;
    double fetchesUntraced = 0, fetchesFull = 0;
    size_t shadedAlike = 0, pixels = 0;
    for (int y = 0; y < image; ++y)
        for (int x = 0; x < image; ++x) {
            const glm::vec4 a = traceUntraced[size_t(y) * image + x];
            if (a.w == 0.0f) continue;
            fetchesUntraced += std::floor(a.w);
            fetchesFull += std::floor(traceFull[size_t(y) * image + x].w);
            glm::dvec2 uv0;
            glm::dvec3 toEye;
            if (!planePixelRay(camera, 2.0f, x, y, image, image, uv0, toEye)) continue;
            const auto hitFlat = exactFlat.traceView(uv0, toEye, material.depthScale);
            const auto hitSum = exactSum.traceView(uv0, toEye, material.depthScale);
            if (!hitFlat || !hitSum) continue;
            toFlat.push_back(glm::length(glm::dvec2(a.x, a.y) - hitFlat->uv) * N);
            toSum.push_back(glm::length(glm::dvec2(a.x, a.y) - hitSum->uv) * N);
            // Shading at the same texcoords: B's slopes are in both, so pixels whose hits agree
            // shade alike; a B left out of the shading too would change most of them.
            if (glm::length(glm::vec2(a) - glm::vec2(traceFull[size_t(y) * image + x])) * N < 0.05f) {
                ++pixels;
                float diff = 0.0f; // colour rows top first, trace rows bottom first
                for (int c = 0; c < 3; ++c)
                    diff = std::max(diff, std::abs(colorUntraced.at(x, image - 1 - y, c) - colorFull.at(x, image - 1 - y, c)));
                shadedAlike += diff <= 2.5f / 255;
            }
        }
    ASSERT_GT(toFlat.size(), 1000u);
    EXPECT_LT(statistics(toFlat).mean, 0.05) << "texels from the exact intersection of the traced part";
    EXPECT_GT(statistics(toSum).mean, 0.2) << "texels from the full sum's intersection: B must be out of the trace";
    EXPECT_NEAR(fetchesUntraced / fetchesFull, 0.5, 0.1) << "one fetch per step instead of two";
    ASSERT_GT(pixels, 100u);
    EXPECT_GT(double(shadedAlike) / double(pixels), 0.95) << "of the pixels hit alike shade alike";
}

// Bounded searches (SurfaceMaterial::boundedSearch, each layer's bounds) on waves that keep to the
// middle of the depth, as the ocean's do, with the ocean's 8..40 samples: the hits keep the exact
// intersection of the sum, the shadows agree with the unbounded search's, and fewer heights are
// read (the steps are no longer; the depths above the path's maximum and below its minimum go).
TEST_F(LayeredSurface, BoundedSearchesKeepTheHitsAndReadFewerHeights) {
    const Layers l = makeLayers(cl(), 0.4);
    const SurfaceLayer layered[] = {{.textures = &l.surfaceA->textures(), .weight = kWeightA},
                                    {.textures = &l.surfaceB->textures(), .texcoordScale = 2.0f, .weight = kWeightB}};
    DirectionalLight light;
    light.direction = {0.6f, 0.55f, 0.3f};
    LayerShot shot;
    const Camera& camera = shot.camera;
    constexpr int image = kImage;
    const HeightFieldTracer exact(l.sum, N, N, EdgeMode::Wrap);
    for (const Technique technique : {Technique::ParallaxOcclusion, Technique::Relief}) {
        SurfaceMaterial material{.depthScale = 0.1f, .minSamples = 8, .maxSamples = 40, .lodThreshold = 100.0f, .shadows = true};
        const auto traceWith = [&](bool bounded) {
            material.boundedSearch = bounded;
            shot.target.bind();
            shot.target.clear();
            shot.renderer.draw(shot.plane, glm::mat4(1.0f), layered, material, camera, light,
                               {.technique = technique, .traceOutput = true});
            return shot.target.readTrace();
        };
        const std::vector<glm::vec4> bounded = traceWith(true), plain = traceWith(false);
        std::vector<double> toExact;
        double fetchesBounded = 0.0, fetchesPlain = 0.0;
        size_t lit = 0, litAlike = 0;
        for (int y = 0; y < image; ++y)
            for (int x = 0; x < image; ++x) {
                const glm::vec4 a = bounded[size_t(y) * image + x], b = plain[size_t(y) * image + x];
                if (a.w == 0.0f) continue;
                fetchesBounded += std::floor(a.w);
                fetchesPlain += std::floor(b.w);
                ++lit;
                litAlike += std::abs(2.0f * (a.w - std::floor(a.w)) - 2.0f * (b.w - std::floor(b.w))) < 0.1f;
                glm::dvec2 uv0;
                glm::dvec3 toEye;
                if (!planePixelRay(camera, 2.0f, x, y, image, image, uv0, toEye)) continue;
                if (const auto hit = exact.traceView(uv0, toEye, material.depthScale))
                    toExact.push_back(glm::length(glm::dvec2(a.x, a.y) - hit->uv) * N);
            }
        const char* name = techniqueName(technique);
        std::printf("[bounded %s] mean %.4f texels, fetches %.1f vs %.1f, light alike %.2f%%\n", name,
                    statistics(toExact).mean, fetchesBounded / double(lit), fetchesPlain / double(lit),
                    100.0 * double(litAlike) / double(lit));
        ASSERT_GT(toExact.size(), 1000u);
        // (Measured 0.0004 and 0.0014 texels; bounds 0.05 too tight on the heights give 0.012.)
        EXPECT_LT(statistics(toExact).mean, 0.005) << name << ": texels from the exact intersection";
        EXPECT_LT(fetchesBounded, 0.9 * fetchesPlain) << name << ": heights read, the bounds' own included";
        EXPECT_GT(double(litAlike) / double(lit), 0.97) << name << ": light within 0.1 of the unbounded shadow's";
    }
}

TEST_F(LayeredSurface, RefusesWhatItCannotDraw) {
    const Layers l = makeLayers(cl());
    SurfaceRenderer renderer;
    const Mesh plane(makePlane({}));
    const Camera camera = accuracyCamera(30.0);
    const SurfaceMaterial material;
    auto draw = [&](std::vector<SurfaceLayer> layers, Technique t = Technique::ParallaxOcclusion) {
        return messageOf([&] { renderer.draw(plane, glm::mat4(1.0f), layers, material, camera, {}, {.technique = t}); });
    };
    const SurfaceTextures* a = &l.surfaceA->textures();
    const SurfaceTextures* b = &l.surfaceB->textures();
    EXPECT_NE(draw({{a, 1.0f, 0.5f}, {b, 2.0f, 0.4f}}).find("sum to 1"), std::string::npos);
    EXPECT_NE(draw({{a, 1.0f, 0.5f}, {b, 2.0f, 0.5f}}, Technique::Hierarchical).find("one grid"), std::string::npos);
    EXPECT_NE(draw({{a, 1.0f, 0.5f}, {nullptr, 2.0f, 0.5f}}).find("no textures"), std::string::npos);
    EXPECT_NE(draw({{a, -1.0f, 0.5f}, {b, 2.0f, 0.5f}}).find("texcoordScale"), std::string::npos);
    EXPECT_NE(draw({}).find("1 to 4 layers"), std::string::npos);
    EXPECT_NE(draw({{a, 1.0f, 0.5f, false}, {b, 2.0f, 0.5f}}).find("always traced"), std::string::npos);
    EXPECT_NE(draw({{a, 1.0f, 0.4f}, {b, 2.0f, 0.3f, false}, {b, 4.0f, 0.3f}}).find("traced layers come first"),
              std::string::npos);
    EXPECT_NE(draw({{a, 1.0f, 0.5f}, {b, 2.0f, 0.5f, false, 1.5f}}).find("restHeight"), std::string::npos);
    SurfaceTextures clamped({.width = 8, .height = 8, .mipmaps = false, .edges = EdgeMode::Clamp});
    EXPECT_NE(draw({{a, 1.0f, 0.5f}, {&clamped, 2.0f, 0.5f}}).find("does not tile"), std::string::npos);
    // A layer in another format than layer 0's (the device's: float32 or float16).
    const SurfaceFormat other =
        a->config().format == SurfaceFormat::Float16 ? SurfaceFormat::Float32 : SurfaceFormat::Float16;
    SurfaceTextures unlike({.width = 8, .height = 8, .mipmaps = false, .format = other});
    EXPECT_NE(draw({{a, 1.0f, 0.5f}, {&unlike, 2.0f, 0.5f}}).find("one format"), std::string::npos);
}

} // namespace
} // namespace hfx::test
