// The one surface pipeline: every user runs it exactly once per frame (and once when made),
// the normals it stores for one depth draw as the normals of any other, and a map from files
// gets everything a generated field gets (formats, transfer paths, the height pyramid).

#include "support/Fields.h"
#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/StaticField.h"
#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/core/SurfaceMaps.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/ImageSurface.h"
#include "hfx/effects/OceanEffect.h"
#include "hfx/effects/SineWavesEffect.h"
#include "hfx/tools/AccuracyProbe.h"

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <cstdlib>
#include <string>
#include <random>
#include <optional>

namespace hfx::test {
namespace {

class Pipeline : public DeviceTest {
protected:
    /// Sobel launches (either kernel) while `f` runs.
    std::uint64_t sobelRuns(const std::function<void()>& f) {
        const auto count = [&] { return cl().launches("sobel") + cl().launches("sobel4"); };
        const std::uint64_t before = count();
        f();
        return count() - before;
    }
};

std::string writeMap(const std::string& name, const std::vector<float>& heights, int size) {
    Image image{size, size, 1, std::vector<float>(heights.size())};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) image.at(x, size - 1 - y, 0) = heights[size_t(y) * size + x];
    const std::string path = outputPath(name);
    writeImage(path, image);
    return path;
}

TEST_F(Pipeline, EveryUserRunsItOnceWhenMadeAndOncePerUpdate) {
    const std::string map = writeMap("pipeline_map.exr", sumOfSines(32, {{0.3, 1, 2, 0.4}}), 32);
    struct User {
        const char* name;
        std::function<std::unique_ptr<Effect>()> make;
        std::uint64_t perUpdate;
    };
    const User users[] = {
        {"sine waves", [&] { return std::make_unique<SineWavesEffect>(cl(), SineWavesConfig{.waves = {.size = 64}}); }, 1},
        {"ocean", [&] { return std::make_unique<OceanEffect>(cl(), OceanEffectConfig{.ocean = {.size = 64, .cascades = 1}}); }, 1},
        {"ocean of three cascades, a pipeline each",
         [&] { return std::make_unique<OceanEffect>(cl(), OceanEffectConfig{.ocean = {.size = 128, .cascades = 3, .cascadeRatio = 2.6f}}); },
         3},
        {"decal wall", [&] { return std::make_unique<DecalWallEffect>(cl(), DecalWallConfig{.bricks = {.size = 64}}); }, 1},
        {"decal wall with a normal map",
         [&] {
             // A flat normal map: (0, 0, 1) stored as (0.5, 0.5, 1).
             const std::string normals = outputPath("pipeline_normals.png");
             Image flat{32, 32, 3, std::vector<float>(32 * 32 * 3, 0.5f)};
             for (int i = 0; i < 32 * 32; ++i) flat.pixels[i * 3 + 2] = 1.0f;
             writeImage(normals, flat);
             return std::make_unique<DecalWallEffect>(cl(), DecalWallConfig{.maps = readSurfaceMaps(map, normals, "")});
         },
         1},
        {"gas planet",
         [&] {
             return std::make_unique<GasPlanetEffect>(cl(), GasPlanetConfig{.gas = {.width = 32, .height = 16, .initialBands = 2}});
         },
         1},
        {"image surface", [&] { return std::make_unique<ImageSurface>(cl(), ImageSurfaceConfig{.maps = readSurfaceMaps(map, "", "")}); }, 0},
    };
    for (const User& user : users) {
        std::unique_ptr<Effect> effect;
        // The detail pass derives its base normals once too: one more Sobel, at construction only.
        const std::uint64_t made = sobelRuns([&] { effect = user.make(); });
        EXPECT_EQ(made, std::string(user.name).find("normal map") != std::string::npos ? 2u : std::max<std::uint64_t>(user.perUpdate, 1u))
            << user.name;
        EXPECT_EQ(sobelRuns([&] { effect->update(0.05); }), user.perUpdate) << user.name;
        EXPECT_EQ(sobelRuns([&] {
                      effect->beginUpdate(0.05);
                      effect->endUpdate();
                  }),
                  user.perUpdate)
            << user.name;
    }
    EXPECT_EQ(sobelRuns([&] { AccuracyProbe probe(cl(), sumOfSines(32, {{0.2, 1, 1, 0}}), 32, 0.1f); }), 1u);
}

TEST_F(Pipeline, NormalsStoredForOneDepthDrawAsTheNormalsOfAnother) {
    // The material owns the depth: the renderer rescales stored normals (made for normalDepth)
    // to the depth it draws. Normals made for 0.02 and for 0.1, both drawn at 0.1, must light
    // alike; drawn at 0.02 instead, the same surface looks different (so the check has teeth).
    constexpr int N = 64;
    const auto heights = sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.12, -1, 3, 0.7}});
    StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
    SurfacePipeline shallow(cl(), SurfacePipelineConfig::of(field, 0.02f, {.mipmaps = false}));
    SurfacePipeline deep(cl(), SurfacePipelineConfig::of(field, 0.1f, {.mipmaps = false}));
    shallow.run(field.buffer());
    deep.run(field.buffer());
    EXPECT_FLOAT_EQ(shallow.textures().config().normalDepth, 0.02f);

    const Mesh plane(makePlane({.size = 2.0f}));
    const Camera camera = cameraAtAngle(35.0, 6.0f, 1.0f);
    SurfaceRenderer renderer;
    RenderTarget target(128, 128);
    auto draw = [&](const SurfacePipeline& p, float depth) {
        target.bind();
        target.clear();
        renderer.draw(plane, glm::mat4(1.0f), p.textures(), {.depthScale = depth, .lodThreshold = 100.0f, .shadows = false},
                      camera, {});
        return target.readColor();
    };
    const Image a = draw(shallow, 0.1f), b = draw(deep, 0.1f), c = draw(deep, 0.02f);
    double worst = 0.0, differs = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        worst = std::max(worst, double(std::abs(a.pixels[i] - b.pixels[i])));
        differs = std::max(differs, double(std::abs(c.pixels[i] - b.pixels[i])));
    }
    // Float32 normals rescaled in slope space are exact up to rounding: one 8-bit step allowed.
    EXPECT_LE(worst, 1.0 / 255 + 1e-6);
    EXPECT_GT(differs, 0.1) << "the depth drawn does not change the shading: the comparison above proves nothing";
}

TEST_F(Pipeline, MapsFromFilesTakeEveryFormatPathAndTheirBounds) {
    constexpr int N = 64;
    const auto heights = sumOfSines(N, {{0.25, 1, 2, 0.5}, {0.1, 3, -1, 0.0}});
    const std::string map = writeMap("pipeline_formats.exr", heights, N); // float: the heights as they are
    const auto sobel = sobelReference(heights, N, 0.08f);
    for (SurfaceFormat format : kSurfaceFormats)
        for (TransferPath path : {TransferPath::Map, TransferPath::PixelBuffer}) {
            const bool hasPyramid = format != SurfaceFormat::Unorm8;
            ImageSurface surface(cl(), {.maps = readSurfaceMaps(map, "", ""),
                                        .material = {.depthScale = 0.08f},
                                        .surface = {.mipmaps = false, .format = format, .transfer = path}});
            EXPECT_EQ(surface.transferPath(), path);
            const std::vector<float> texels = readSurface(surface.textures());
            // Each format's rounding: none, half floats near 1 (2^-11), half a step of 1/255 (the
            // normal's n/2 + 1/2 doubles it).
            const double bound = format == SurfaceFormat::Float32 ? 1e-6 : format == SurfaceFormat::Float16 ? 1e-3 : 1.0 / 255 + 1e-6;
            double worst = 0.0;
            for (size_t i = 0; i < texels.size(); ++i) {
                const double stored = format == SurfaceFormat::Unorm8 && i % 4 != 3 ? texels[i] * 2.0 - 1.0 : texels[i];
                worst = std::max(worst, std::abs(stored - sobel[i]));
            }
            EXPECT_LE(worst, bound) << surfaceFormatName(format) << ", " << transferPathName(path);
            ASSERT_EQ(carriesBounds(surface.textures().config()), hasPyramid);
            if (!hasPyramid) continue;
            // Every level where the device's layout holds it: the bounds of the heights as stored
            // (rounded to the format), which are what the tracers read.
            std::vector<float> storedHeights(size_t(N) * N);
            for (size_t i = 0; i < storedHeights.size(); ++i) storedHeights[i] = texels[4 * i + 3];
            const auto pyramid = pyramidReference(storedHeights, N, N);
            const SurfaceTextures& t = surface.textures();
            size_t offset = 0;
            for (int level = 0; level < HeightBounds(t.config()).levels(); ++level) {
                const std::vector<float> stored = readPyramidLevel(t, level); // (max, min) pairs
                EXPECT_EQ(stored, std::vector<float>(pyramid.begin() + offset, pyramid.begin() + offset + stored.size()))
                    << surfaceFormatName(format) << ", level " << level;
                offset += stored.size();
            }
            EXPECT_EQ(offset, pyramid.size());
        }
}

TEST_F(Pipeline, AutoStoresFloat16OnAGpuAndFloat32WhereTheDeviceAsksForIt) {
    // SurfaceFormat::Auto, every effect's default: a GPU's half floats (half the bytes to move
    // and to sample), a CPU rasteriser's float32 (GlWorkarounds::float32Surfaces); a format
    // asked for is itself on either.
    const GlWorkarounds gpu{}, cpu{.float32Surfaces = true};
    EXPECT_EQ(chooseSurfaceFormat(SurfaceFormat::Auto, gpu), SurfaceFormat::Float16);
    EXPECT_EQ(chooseSurfaceFormat(SurfaceFormat::Auto, cpu), SurfaceFormat::Float32);
    for (const SurfaceFormat format : kSurfaceFormats) {
        EXPECT_EQ(chooseSurfaceFormat(format, gpu), format) << surfaceFormatName(format);
        EXPECT_EQ(chooseSurfaceFormat(format, cpu), format) << surfaceFormatName(format);
    }
    EXPECT_EQ(SurfaceOptions{}.format, SurfaceFormat::Auto);
    EXPECT_EQ(parseSurfaceFormat("auto"), SurfaceFormat::Auto);

    // A pipeline of the default options stores the chosen format, in GL too, its texels the
    // Sobel normals and heights to that format's rounding (half floats round: some texel shows it).
    constexpr int N = 32;
    const auto heights = sumOfSines(N, {{0.3, 1, 2, 0.3}, {0.1, 3, -1, 0.0}});
    const auto sobel = sobelReference(heights, N, 0.05f);
    for (const bool float32 : {false, true}) {
        const WorkaroundsSet set(float32 ? "float32-surfaces=1" : "float32-surfaces=0");
        const SurfaceFormat expected = float32 ? SurfaceFormat::Float32 : SurfaceFormat::Float16;
        StaticField field(cl(), N, N, EdgeMode::Wrap, heights);
        SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.05f, {.mipmaps = false}));
        surface.run(field.buffer());
        EXPECT_EQ(surface.config().options.format, expected);
        EXPECT_EQ(surface.textures().config().format, expected);
        EXPECT_NE(surface.transferDescription().find(surfaceFormatName(expected)), std::string::npos)
            << surface.transferDescription();
        GLint internal = 0;
        glGetTextureLevelParameteriv(surface.textures().surface(), 0, GL_TEXTURE_INTERNAL_FORMAT, &internal);
        EXPECT_EQ(internal, float32 ? GL_RGBA32F : GL_RGBA16F);
        const std::vector<float> texels = readSurface(surface.textures());
        ASSERT_EQ(texels.size(), sobel.size());
        double worst = 0.0;
        for (size_t i = 0; i < texels.size(); ++i) worst = std::max(worst, double(std::abs(texels[i] - sobel[i])));
        EXPECT_LE(worst, float32 ? 1e-6 : 1e-3) << surfaceFormatName(expected);
        if (!float32) {
            EXPECT_GT(worst, 1e-6) << "float16 texels equal float32's: not stored as half floats";
        }
    }

    // A stored format is needed where texels are laid out: Auto there is refused by name.
    const auto refusal = [](const std::function<void()>& f) {
        try {
            f();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(refusal([] { texelBytes(SurfaceFormat::Auto); }).find("auto"), std::string::npos);
    const std::string unstored =
        refusal([] { SurfaceTextures t({.width = 8, .height = 8, .format = SurfaceFormat::Auto}); });
    EXPECT_NE(unstored.find("format is auto"), std::string::npos) << unstored;
}

TEST_F(Pipeline, ThePyramidGlBuildsFromTheTexelsIsTheComputeDevicesToTheBit) {
    // BoundsPass builds the bounds from what GL holds; on a CPU rasteriser a float32 surface's
    // come from the compute device (GlWorkarounds::pyramidFromCompute, SurfacePipeline::bounds)
    // while a draw reads them. Both, on an oblong field with isolated spikes and pits (a wrong
    // corner or a lost lone row shows), in either layout and edge mode, must hold the same
    // bounds to the bit, and where the field wraps the plain reference's. The device stops
    // building them once no draw reads them.
    constexpr int W = 64, H = 16;
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> heights(size_t(W) * H);
    for (float& h : heights) {
        const float r = unit(random);
        h = r < 0.02f ? 0.9f : r < 0.04f ? 0.1f : 0.3f + 0.4f * unit(random); // no 0 or 1: an empty read shows
    }
    const auto reference = pyramidReference(heights, W, H);
    for (const PyramidLayout layout : {PyramidLayout::Atlas, PyramidLayout::MipChain})
        for (const EdgeMode edges : {EdgeMode::Wrap, EdgeMode::Clamp}) {
            std::vector<float> built[2];
            for (int fromCompute = 0; fromCompute < 2; ++fromCompute) {
                const WorkaroundsSet set(str("pyramid-atlas=", layout == PyramidLayout::Atlas ? 1 : 0,
                                             ",pyramid-from-compute=", fromCompute).c_str());
                StaticField field(cl(), W, H, edges, heights);
                // Float32 texels: the device builds only those (their heights are its own).
                const SurfaceOptions float32{.mipmaps = false, .format = SurfaceFormat::Float32};
                SurfacePipeline surface(cl(), SurfacePipelineConfig::of(field, 0.05f, float32));
                surface.run(field.buffer());
                ASSERT_EQ(surface.bounds() != nullptr, fromCompute == 1);
                const HeightBounds levels(surface.textures().config(), layout);
                if (fromCompute) {
                    EXPECT_EQ(surface.bounds()->layout(), layout);
                    EXPECT_FALSE(surface.bounds()->holds(surface.textures())) << "built before any draw read them";
                    surface.bounds()->noteWanted(); // as the exact tracer does
                    surface.run(field.buffer());
                    ASSERT_TRUE(surface.bounds()->holds(surface.textures())) << "the device's bounds were not uploaded";
                }
                for (int level = 0; level < levels.levels(); ++level) {
                    const std::vector<float> stored = fromCompute ? readBoundsLevel(*surface.bounds(), level)
                                                                  : readPyramidLevel(surface.textures(), level, layout);
                    built[fromCompute].insert(built[fromCompute].end(), stored.begin(), stored.end());
                }
                if (fromCompute) {
                    surface.run(field.buffer()); // read by no draw since
                    EXPECT_FALSE(surface.bounds()->holds(surface.textures())) << "built though no draw read them";
                }
            }
            const char* where = layout == PyramidLayout::Atlas ? "atlas" : "mip chain";
            EXPECT_EQ(built[0], built[1]) << where << ", " << edgeModeName(edges);
            if (edges == EdgeMode::Wrap) {
                EXPECT_EQ(built[0], reference) << where;
            }
        }
}

TEST_F(Pipeline, ANormalMapOverUnchangingHeightsIsStoredExactly) {
    constexpr int N = 32;
    const auto heights = sumOfSines(N, {{0.3, 1, 1, 0.2}});
    const std::string map = writeMap("pipeline_nm_height.exr", heights, N);
    Image normals{N, N, 3, std::vector<float>(N * N * 3)};
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            normals.at(x, y, 0) = 0.5f + 0.3f * std::sin(0.4f * x);
            normals.at(x, y, 1) = 0.5f - 0.2f * std::cos(0.3f * y);
            normals.at(x, y, 2) = 0.9f;
        }
    const std::string normalMap = outputPath("pipeline_nm.exr");
    writeImage(normalMap, normals);
    const std::vector<float> expected = packNormalMap(readImage(normalMap), normalMap, heights);
    ImageSurface surface(cl(), {.maps = readSurfaceMaps(map, normalMap, ""),
                                .surface = {.mipmaps = false, .format = SurfaceFormat::Float32}});
    EXPECT_EQ(readSurface(surface.textures()), expected);
    // A static surface derives once: later updates change nothing and refuse a bad dt.
    surface.update(0.1);
    EXPECT_EQ(readSurface(surface.textures()), expected);
    EXPECT_NE(messageOf([&] { surface.update(-1.0); }).find("dt"), std::string::npos);
}

} // namespace
} // namespace hfx::test

namespace hfx::test {
namespace {

/// What drawHalves saw: the pixels it checked on each half, and the largest difference from the
/// expected colour with the first pixel that differs by more than 2/255.
struct HalvesCheck {
    int checked[2] = {0, 0};
    float worst = 0.0f;
    std::string first;
};

/// An 8x8 surface of albedo 0.3 whose shading channels (RGBA8) are `left` where u < 0.5 and
/// `right` elsewhere, normal mapped on a 2-unit plane seen from accuracyCamera(0) into 64x64
/// pixels under `light`. Each pixel showing the surface away from the halves' border and the wrap
/// at u = 0 (where filtering mixes them) is held to expected(uv, inLeft), the linear colour,
/// within 2/255 once gamma encoded.
template <class Expected>
HalvesCheck drawHalves(std::array<unsigned char, 4> left, std::array<unsigned char, 4> right,
                       const SurfaceMaterial& material, const DirectionalLight& light, Expected&& expected) {
    constexpr int N = 8, kImage = 64;
    SurfaceTextures textures({.width = N, .height = N, .mipmaps = false});
    textures.setAlbedo(Image{1, 1, 3, {0.3f, 0.3f, 0.3f}});
    std::vector<unsigned char> channels(4 * N * N);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) std::copy_n((x < N / 2 ? left : right).data(), 4, &channels[4 * size_t(y * N + x)]);
    textures.uploadChannels(channels.data());
    const Mesh plane(makePlane({.size = 2.0f}));
    SurfaceRenderer renderer;
    RenderTarget target(kImage, kImage, true);
    target.bind();
    target.clear();
    renderer.draw(plane, glm::mat4(1.0f), textures, material, accuracyCamera(0.0), light,
                  {.technique = Technique::NormalMapping, .traceOutput = true});
    const Image color = target.readColor();
    const std::vector<glm::vec4> trace = target.readTrace();
    HalvesCheck result;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            const glm::vec4 t = trace[size_t(y) * kImage + x];
            if (t.w == 0.0f || std::abs(t.x - 0.5f) < 0.2f || t.x < 0.07f || t.x > 0.93f) continue;
            const bool inLeft = t.x < 0.5f;
            const glm::vec3 linear = expected(glm::vec2(t), inLeft);
            for (int c = 0; c < 3; ++c) {
                const float off = std::abs(color.at(x, kImage - 1 - y, c) - std::pow(std::min(linear[c], 1.0f), 1.0f / 2.2f));
                if (off > 2.0f / 255.0f && result.first.empty())
                    result.first = str(inLeft ? "left" : "right", " pixel ", x, ",", y, " channel ", c, " off by ", off);
                result.worst = std::max(result.worst, off);
            }
            ++result.checked[inLeft ? 0 : 1];
        }
    return result;
}

// The shading channels: a surface half covered by roughness 1 and occlusion 0 (the inside of a
// fresh crater) loses its ambient light and its highlight there, by the lit model's formula.
TEST_F(Pipeline, ShadingChannelsTakeTheAmbientAndTheHighlightWhereTheySaySo) {
    const SurfaceMaterial material{.depthScale = 0.05f, .shadows = false, .specularStrength = 0.2f, .specularPower = 32.0f};
    DirectionalLight light;
    light.direction = {0.0f, 1.0f, 0.0f}; // straight down the view: the highlight's peak everywhere
    // The lit model (shade/lit.glsl) with N = L = up: diffuse 1; the Blinn-Phong lobe at the
    // pixel's half vector, where roughness 1 turns the power P into P / (1 + P) and the
    // normalisation (P' + 2) / (P + 2) follows.
    const float albedo = 77.0f / 255.0f, P = 32.0f, roughP = P / (1.0f + P);
    const glm::vec3 eye = accuracyCamera(0.0).position;
    auto lobe = [&](glm::vec2 uv, float power) {
        const glm::vec3 point((uv.x - 0.5f) * 2.0f, 0.0f, -(uv.y - 0.5f) * 2.0f); // makePlane's layout
        const glm::vec3 h = glm::normalize(glm::normalize(light.direction) + glm::normalize(eye - point));
        return (power + 2.0f) / (P + 2.0f) * std::pow(h.y, power);
    };
    // The crater's half: roughness 1, occlusion 0; the open half: neither. No heat.
    const HalvesCheck seen = drawHalves({255, 0, 0, 0}, {0, 255, 0, 0}, material, light, [&](glm::vec2 uv, bool crater) {
        return crater ? albedo * light.color + 0.2f * light.color * lobe(uv, roughP)
                      : albedo * (light.ambient + light.color) + 0.2f * light.color * lobe(uv, P);
    });
    EXPECT_LE(seen.worst, 2.0f / 255.0f) << seen.first;
    EXPECT_GT(seen.checked[0], 200);
    EXPECT_GT(seen.checked[1], 200);
}

// The channels' heat (A): a surface half hot emits embers' light there, added to what the lit
// model reflects, lit or not: 2.5 t^2 (1, 0.12 + 0.6 t^2, 0.02 + 0.4 t^4) (shade/lit.glsl's
// hfx_ember), and nothing where it is cold.
TEST_F(Pipeline, HeatInTheChannelsGlowsAsEmbers) {
    constexpr unsigned char kHeat = 100;
    const float albedo = 77.0f / 255.0f;
    const glm::vec3 ember(emberReference(kHeat / 255.0));
    const SurfaceMaterial material{.depthScale = 0.05f, .shadows = false, .specularStrength = 0.0f};
    for (const float up : {1.0f, -1.0f}) { // lit from straight above, then from below (no direct light)
        DirectionalLight light;
        light.direction = {0.0f, up, 0.0f};
        const HalvesCheck seen = drawHalves({0, 255, 0, kHeat}, {0, 255, 0, 0}, material, light, [&](glm::vec2, bool hot) {
            return albedo * (light.ambient + (up > 0.0f ? light.color : glm::vec3(0.0f))) + (hot ? ember : glm::vec3(0.0f));
        });
        EXPECT_LE(seen.worst, 2.0f / 255.0f) << seen.first << " (light " << up << ")";
        EXPECT_GT(seen.checked[0], 200);
        EXPECT_GT(seen.checked[1], 200);
    }
}

} // namespace
} // namespace hfx::test

namespace hfx::test {
namespace {

// The decal pass runs when the maps would change: an impact, or a heal curve moving (read on
// the log's heal clock, healStep apart, the glow on its own, glowStep apart); a still wall costs
// no decal pass.
TEST_F(Pipeline, TheWallRebuildsItsDecalsOnlyWhenTheyWouldChange) {
    DecalWallEffect wall(cl(), {.bricks = {.size = 64}});
    // The glow cools from 0 s for 3 s; the roughness heals from 5 s on, for 30 s.
    const DamageLook& look = wall.config().damage.look;
    auto passes = [&] { return cl().launches("decals"); };
    wall.update(0.1);
    const std::uint64_t start = passes();
    for (int i = 0; i < 5; ++i) wall.update(0.1);
    EXPECT_EQ(passes(), start) << "nothing changed";
    wall.shoot(0.5, 0.5);
    wall.update(0.1);
    EXPECT_EQ(passes(), start + 1) << "an impact";
    for (int i = 0; i < 10; ++i) wall.update(0.1); // 1 s: each update crosses glow steps
    EXPECT_EQ(passes(), start + 1 + 10) << "the crater's glow cools: a pass each update";
    wall.update(look.glow.duration); // 4.1 s
    const std::uint64_t cooled = passes();
    for (int i = 0; i < 5; ++i) wall.update(0.1);
    EXPECT_EQ(passes(), cooled) << "no curve moves between " << look.glow.duration << " and " << look.roughness.start
                                << " s";
    wall.update(look.roughness.start);
    EXPECT_EQ(passes(), cooled + 1) << "the roughness began to heal";
    const std::uint64_t healing = passes();
    for (int i = 0; i < 25; ++i) wall.update(0.01); // 0.25 s: two or three heal steps of 0.125 s
    EXPECT_GE(passes(), healing + 2);
    EXPECT_LE(passes(), healing + 3);
    wall.update(100.0);
    const std::uint64_t healed = passes();
    wall.update(0.5);
    EXPECT_EQ(passes(), healed) << "every curve has reached its end";
    wall.clearDamage();
    wall.update(0.1);
    EXPECT_EQ(passes(), healed + 1);
}

} // namespace
} // namespace hfx::test

namespace hfx::test {
namespace {

// Noise put to use: the wall's stone grain is its bricks plus the NoiseField's heights, as
// documented, and nothing else; the planet draws its flow detail's heights.
TEST_F(Pipeline, NoiseGrainsTheWallAndDetailsThePlanetsCloudTops) {
    const DecalWallConfig config{.bricks = {.size = 64}};
    DecalWallEffect wall(cl(), config);
    const BrickWallMaps bricks = makeBrickWall(config.bricks);
    NoiseConfig grainConfig = config.grainNoise;
    grainConfig.width = grainConfig.height = 64;
    NoiseField grain(cl(), grainConfig);
    const std::vector<float> noise = readHeights(cl(), grain);
    const std::vector<float> walls = wall.readHeights();
    double moved = 0;
    for (size_t i = 0; i < walls.size(); ++i) {
        ASSERT_EQ(walls[i], std::clamp(bricks.heights[i] + config.grain * (noise[i] - 0.5f), 0.0f, 1.0f)) << i;
        moved = std::max(moved, double(std::abs(walls[i] - bricks.heights[i])));
    }
    EXPECT_GT(moved, 0.01) << "the grain shows";
    DecalWallEffect plain(cl(), {.bricks = {.size = 64}, .grain = 0.0f});
    EXPECT_EQ(plain.readHeights(), bricks.heights);

    // The planet's cloud tops: its drawn surface is its flow detail's heights (FlowDetailTest
    // holds those to the shared math), at the detail's scale per gas cell, the device's when
    // left to it.
    GasPlanetEffect planet(cl(), {.gas = {.width = 64, .height = 32, .initialBands = 4.0f}, .stormsPerSecond = 0.0f,
                                  .surface = {.format = SurfaceFormat::Float32}}); // its heights to the bit
    planet.update(0.1);
    ASSERT_NE(planet.detail(), nullptr);
    const int scale = autoDetailScale(cl(), 64);
    EXPECT_EQ(planet.detail()->config().scale, scale);
    EXPECT_EQ(planet.surfaceWidth(), 64 * scale);
    EXPECT_EQ(planet.surfaceHeight(), 32 * scale);
    EXPECT_EQ(planet.detail()->config().capRows, 0.04f * 32.0f);
    std::vector<float> drawn(size_t(planet.surfaceWidth()) * planet.surfaceHeight());
    const std::vector<float> surface = readSurface(planet.textures());
    for (size_t i = 0; i < drawn.size(); ++i) drawn[i] = surface[4 * i + 3];
    EXPECT_EQ(drawn, planet.readHeights());
    GasPlanetEffect plainPlanet(cl(), {.gas = {.width = 64, .height = 32, .initialBands = 4.0f}, .stormsPerSecond = 0.0f,
                                       .poleCap = 0.0f, .detail = {.amount = 0.0f}});
    EXPECT_EQ(plainPlanet.detail(), nullptr);
    EXPECT_EQ(plainPlanet.surfaceWidth(), 64);
}

} // namespace
} // namespace hfx::test
