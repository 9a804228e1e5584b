// The shader side's contracts: the uniform blocks have the layout their C++ mirrors claim, every
// tracer runs outside the fragment stage through the accessor contract (shaders/trace/README.md,
// here a compute shader over the same textures) and lands where the exact intersection says, and
// the technique table is what the docs print.

#include "support/Fields.h"
#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/compute/StaticField.h"
#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/SurfaceUniforms.h"
#include "hfx/effects/tracer/BoundsPass.h"
#include "hfx/effects/tracer/TexelShadowPass.h"
#include "hfx/tools/AccuracyProbe.h"

#include <bit>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <utility>

namespace hfx::test {
namespace {

class TracerContract : public DeviceTest {};

GLint offsetOf(GLuint program, const char* name) {
    GLuint index = GL_INVALID_INDEX;
    glGetUniformIndices(program, 1, &name, &index);
    if (index == GL_INVALID_INDEX) return -1;
    GLint offset = -1;
    glGetActiveUniformsiv(program, 1, &index, GL_UNIFORM_OFFSET, &offset);
    return offset;
}

TEST_F(TracerContract, UniformBlocksHaveTheLayoutOfTheirCppMirrors) {
    SurfaceRenderer renderer;
    // Water shading with the hierarchical tracer, bounded searches on two layers, a shadow map
    // received and the motion and a deferred engine's outputs written: the variant that reads
    // every member.
    const GLuint p = renderer
                         .program({.technique = Technique::Hierarchical},
                                  {.shading = Shading::Water, .layers = 2, .boundedSearch = true, .shadowMap = 1,
                                   .motionOutput = 3, .outputs = {.normal = 4, .albedo = 5, .material = 6}})
                         .id();
    const std::pair<const char*, size_t> surface[] = {
        {"u_model", offsetof(SurfaceUniforms, model)},
        {"u_viewProj", offsetof(SurfaceUniforms, viewProj)},
        {"u_normalMatrix", offsetof(SurfaceUniforms, normalMatrix)},
        {"u_patchBounds", offsetof(SurfaceUniforms, patchBounds)},
        {"u_cameraPos", offsetof(SurfaceUniforms, cameraPos)},
        {"u_depthScale", offsetof(SurfaceUniforms, depthScale)},
        {"u_lightDir", offsetof(SurfaceUniforms, lightDir)},
        {"u_normalScale", offsetof(SurfaceUniforms, normalScale)},
        {"u_lightColor", offsetof(SurfaceUniforms, lightColor)},
        {"u_lodThreshold", offsetof(SurfaceUniforms, lodThreshold)},
        {"u_ambient", offsetof(SurfaceUniforms, ambient)},
        {"u_shadowSharpness", offsetof(SurfaceUniforms, shadowSharpness)},
        {"u_normalDecode", offsetof(SurfaceUniforms, normalDecode)},
        {"u_specularStrength", offsetof(SurfaceUniforms, specularStrength)},
        {"u_specularPower", offsetof(SurfaceUniforms, specularPower)},
        {"u_silhouetteFade", offsetof(SurfaceUniforms, silhouetteFade)},
        {"u_minSamples", offsetof(SurfaceUniforms, minSamples)},
        {"u_maxSamples", offsetof(SurfaceUniforms, maxSamples)},
        {"u_shadowSamples", offsetof(SurfaceUniforms, shadowSamples)},
        {"u_clipToPatch", offsetof(SurfaceUniforms, clipToPatch)},
        {"u_varianceFloor", offsetof(SurfaceUniforms, varianceFloor)},
        {"u_fieldLast", offsetof(SurfaceUniforms, fieldLast)},
        {"u_wrapMask", offsetof(SurfaceUniforms, wrapMask)},
        {"u_pixelBudget", offsetof(SurfaceUniforms, pixelBudget)},
        {"u_layerScale", offsetof(SurfaceUniforms, layerScale)},
        {"u_layerWeight", offsetof(SurfaceUniforms, layerWeight)},
        {"u_layerSlope", offsetof(SurfaceUniforms, layerSlope)},
        {"u_layerLevel", offsetof(SurfaceUniforms, layerLevel)},
        {"u_shadowViewProj", offsetof(ShadowUniforms, viewProj)},
        {"u_shadowTile", offsetof(ShadowUniforms, tile)},
        {"u_shadowLookup", offsetof(ShadowUniforms, lookup)},
        {"u_shadowTexel", offsetof(ShadowUniforms, texel)},
        {"u_shadowCount", offsetof(ShadowUniforms, count)},
        {"u_shadowReversedZ", offsetof(ShadowUniforms, reversedZ)},
        {"u_linearOutput", offsetof(SurfaceUniforms, linearOutput)},
        {"u_shadowLight", offsetof(SurfaceUniforms, shadowLight)},
        {"u_texelSize", offsetof(SurfaceUniforms, texelSize)},
        {"u_traceWidth", offsetof(SurfaceUniforms, traceWidth)},
        {"u_traceStamp", offsetof(SurfaceUniforms, traceStamp)},
        {"u_traceOrigin", offsetof(SurfaceUniforms, traceOrigin)},
        {"u_traceHeight", offsetof(SurfaceUniforms, traceHeight)},
        {"u_reversedZ", offsetof(SurfaceUniforms, reversedZ)},
        {"u_previousFromWorld", offsetof(SurfaceUniforms, previousFromWorld)},
        {"u_jitter", offsetof(SurfaceUniforms, jitter)},
        {"u_towardsEye", offsetof(SurfaceUniforms, towardsEye)},
        {"u_orthographic", offsetof(SurfaceUniforms, orthographic)},
        {"u_deepColor", offsetof(WaterUniforms, deepColor)},
        {"u_fresnelF0", offsetof(WaterUniforms, fresnelF0)},
        {"u_shallowColor", offsetof(WaterUniforms, shallowColor)},
        {"u_glintPower", offsetof(WaterUniforms, glintPower)},
        {"u_skyZenith", offsetof(WaterUniforms, skyZenith)},
        {"u_glintStrength", offsetof(WaterUniforms, glintStrength)},
        {"u_skyHorizon", offsetof(WaterUniforms, skyHorizon)},
        {"u_hazeDistance", offsetof(WaterUniforms, hazeDistance)},
        {"u_foam", offsetof(WaterUniforms, foam)},
        {"u_sunGlow", offsetof(WaterUniforms, sunGlow)},
        {"u_translucency", offsetof(WaterUniforms, translucency)},
        {"u_foamCells", offsetof(WaterUniforms, foamCells)},
        {"u_foamColor", offsetof(WaterUniforms, foamColor)},
        {"u_foamRoughness", offsetof(WaterUniforms, foamRoughness)},
        {"u_foamDrift", offsetof(WaterUniforms, foamDrift)},
        {"u_windDirection", offsetof(WaterUniforms, windDirection)},
        {"u_spindrift", offsetof(WaterUniforms, spindrift)},
        {"u_streakCells", offsetof(WaterUniforms, streakCells)},
        {"u_windDirectionFrom", offsetof(WaterUniforms, windDirectionFrom)},
        {"u_spindriftFrom", offsetof(WaterUniforms, spindriftFrom)},
        {"u_cloudHeight", offsetof(WaterUniforms, cloudHeight)},
        {"u_cloudDrift", offsetof(WaterUniforms, cloudDrift)},
        {"u_cloudScale", offsetof(WaterUniforms, cloudScale)},
        {"u_cloudThreshold", offsetof(WaterUniforms, cloudThreshold)},
        {"u_cloudVeil", offsetof(WaterUniforms, cloudVeil)},
        {"u_cloudMeanThickness", offsetof(WaterUniforms, cloudMeanThickness)},
    };
    for (const auto& [name, offset] : surface) EXPECT_EQ(offsetOf(p, name), GLint(offset)) << name;
    for (const auto& [block, size] : {std::pair{"HfxSurface", sizeof(SurfaceUniforms)}, std::pair{"HfxWater", sizeof(WaterUniforms)},
                                      std::pair{"HfxShadows", sizeof(ShadowUniforms)}}) {
        const GLuint index = glGetUniformBlockIndex(p, block);
        ASSERT_NE(index, GL_INVALID_INDEX) << block;
        GLint dataSize = 0;
        glGetActiveUniformBlockiv(p, index, GL_UNIFORM_BLOCK_DATA_SIZE, &dataSize);
        EXPECT_EQ(dataSize, GLint(size)) << block;
    }
    // The planet's block (its rings and their shadows), in the planet shading's variant.
    const GLuint planet = renderer.program({}, {.shading = Shading::Planet}).id();
    const std::pair<const char*, size_t> planetMembers[] = {
        {"u_planetCentre", offsetof(PlanetUniforms, planetCentre)}, {"u_planetRadius", offsetof(PlanetUniforms, planetRadius)},
        {"u_ringAxis", offsetof(PlanetUniforms, ringAxis)},         {"u_ringInner", offsetof(PlanetUniforms, ringInner)},
        {"u_ringOuter", offsetof(PlanetUniforms, ringOuter)},       {"u_sunRadius", offsetof(PlanetUniforms, sunRadius)},
        {"u_ringTexels", offsetof(PlanetUniforms, ringTexels)},
    };
    for (const auto& [name, offset] : planetMembers) EXPECT_EQ(offsetOf(planet, name), GLint(offset)) << name;
    const GLuint index = glGetUniformBlockIndex(planet, "HfxPlanet");
    ASSERT_NE(index, GL_INVALID_INDEX);
    GLint dataSize = 0;
    glGetActiveUniformBlockiv(planet, index, GL_UNIFORM_BLOCK_DATA_SIZE, &dataSize);
    EXPECT_EQ(dataSize, GLint(sizeof(PlanetUniforms)));
    // A triplanar mapping's members, in its variant (the others read none).
    const GLuint triplanar = renderer.program({.technique = Technique::Hierarchical}, {.triplanar = true}).id();
    EXPECT_EQ(offsetOf(triplanar, "u_triplanarScale"), GLint(offsetof(SurfaceUniforms, triplanarScale)));
    EXPECT_EQ(offsetOf(triplanar, "u_triplanarSharpness"), GLint(offsetof(SurfaceUniforms, triplanarSharpness)));
}

/// Every harness program starts with this: 64 invocations per group.
const SourceFile kComputeHeader{"harness_header.comp", R"(#version 450 core
layout(local_size_x = 64) in;
)",
                                "test"};

/// A compute-shader harness of the tracer contract: its own accessors over the same textures the
/// renderer reads, then trace/common.glsl and a technique's file, then a main that traces one
/// ray per invocation from a buffer of rays into a buffer of hits.
const SourceFile kHarness{"harness.comp", R"(
layout(binding = HFX_UNIT_SURFACE) uniform sampler2D s_surface;
#if HFX_PYRAMID_ATLAS
layout(rg32f, binding = HFX_IMAGE_PYRAMID) readonly uniform image2D i_pyramid; // SurfaceTextures::bindPyramid
#else
layout(binding = HFX_UNIT_PYRAMID) uniform sampler2D s_pyramid;
#endif
uniform ivec2 u_wrap;
float hfx_height(vec2 uv, float level) { return textureLod(s_surface, uv, level).w; }
ivec2 hfx_size() { return textureSize(s_surface, 0); }
// A cell's samples by a gather of the texture itself (the renderer reads its cells image).
vec4 hfx_cell_samples(ivec2 cell) { return textureGather(s_surface, (vec2(cell) + 1.0) / vec2(hfx_size()), 3); }
vec2 hfx_bounds(ivec2 cell, int level) {
    const ivec2 n = max(hfx_size() >> level, ivec2(1));
    const ivec2 texel = mix(clamp(cell, ivec2(0), n - 1), (cell % n + n) % n, bvec2(u_wrap));
#if HFX_PYRAMID_ATLAS
    // The image's layout (HeightBounds::atlasOrigin), counted level by level.
    ivec2 origin = ivec2(level > 0 ? hfx_size().x : 0, 0);
    for (int k = 1; k < level; ++k) origin.y += max(hfx_size().y >> k, 1);
    return imageLoad(i_pyramid, origin + texel).rg;
#else
    return texelFetch(s_pyramid, texel, level).rg;
#endif
}
vec2 hfx_segment_bounds(vec2 a, vec2 b, float level) { return vec2(1.0, 0.0); } // searches span [0, 1]
float g_fetches = 0.0; // the renderer's accessors count their reads; these do not
)",
                          "test"};
/// The harness's buffers: two vec4 of input per ray (a, b: what each main below says), one vec4
/// out, and the invocation's ray index (false past the count).
const SourceFile kHarnessBuffers{"harness_buffers.comp", R"(
layout(std430, binding = 0) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = 1) writeonly buffer Hits { vec4 hits[]; };
uniform int u_count;
bool hfx_harness_ray(out uint i, out vec4 a, out vec4 b) {
    i = gl_GlobalInvocationID.x;
    if (i >= uint(u_count)) return false;
    a = rays[2 * i];
    b = rays[2 * i + 1];
    return true;
}
)",
                               "test"};
const SourceFile kHarnessMain{"harness_main.comp", R"(
void main() { // a: uv, parallax; b: cos, level, samples, tolerance
    uint i;
    vec4 a, b;
    if (!hfx_harness_ray(i, a, b)) return;
    HfxRay ray;
    ray.uv = a.xy;
    ray.parallax = a.zw;
    ray.cosTheta = b.x;
    ray.level = b.y;
    ray.samples = int(b.z);
    ray.tolerance = b.w;
    ray.start = 0.0;
    const HfxHit hit = hfx_trace(ray);
    hits[i] = vec4(hit.uv, hit.depth, 0.0);
}
)",
                              "test"};

const SourceFile kShadowMain{"harness_shadow.comp", R"(
void main() { // a: uv, span; b: h0, level, samples, sharpness
    uint i;
    vec4 a, b;
    if (!hfx_harness_ray(i, a, b)) return;
    HfxShadowRay ray;
    ray.uv = a.xy;
    ray.span = a.zw;
    ray.h0 = b.x;
    ray.level = b.y;
    ray.samples = int(b.z);
    ray.sharpness = b.w;
    // The caller's shadow: with the renderer's accessors and its texel shadows, read from them
    // where they hold it (surface/shadow.glsl); else the tracer's walk.
    int deferred; // never: the harness has no HFX_DEFERRED_SHADOWS
    const float shadow = hfx_surface_shadow(ray, 1.0, deferred);
    hits[i] = vec4(shadow, g_fetches, 0.0, 0.0);
}
)",
                             "test"};

/// Runs a harness program (64 invocations per group) over `input`, two vec4 per item, on storage
/// buffer 0; returns the vec4 per item it writes to buffer 1. The caller has bound the textures.
std::vector<glm::vec4> runHarness(const ShaderProgram& p, const std::vector<glm::vec4>& input) {
    const int count = int(input.size() / 2);
    GlBuffer in = GlBuffer::create(), out = GlBuffer::create();
    glNamedBufferStorage(in.id(), GLsizeiptr(input.size() * sizeof(glm::vec4)), input.data(), 0);
    glNamedBufferStorage(out.id(), GLsizeiptr(size_t(count) * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    p.set("u_count", count);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    p.use();
    glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> result(static_cast<size_t>(count));
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(result.size() * sizeof(glm::vec4)), result.data());
    glUseProgram(0);
    return result;
}

/// Whose height accessors a harness traces with: its own (kHarness: the contract, outside the
/// renderer) or the renderer's (surface/heights.glsl and its uniform block: what draws use,
/// the pyramid's wrapping across the tile's edges included).
enum class Accessors { Harness, Renderer };

/// Both pyramid layouts, whatever the device draws with: the mip chain a GPU reads (a texelFetch at
/// the level, the patch's samples gathered) and llvmpipe's atlas and cells images.
constexpr PyramidLayout kLayouts[] = {PyramidLayout::MipChain, PyramidLayout::Atlas};
const char* layoutName(PyramidLayout layout) { return layout == PyramidLayout::Atlas ? "atlas" : "mip chain"; }

/// Traces a batch of rays (two vec4 each, as Rays above) with one technique through the compute
/// harness over `textures` (wrapped or clamped as their field's edges say); returns each hit as
/// (u, v, depth fraction, 0), or with kShadowMain each shadow ray's shadow in x and, with the
/// renderer's accessors, the reads it made in y. With the renderer's accessors and `texelShadows`,
/// those texel shadows are read as a draw reads them (HFX_TEXEL_SHADOWS, their light's uniforms,
/// surface/shadow.glsl). The textures' bounds are built here in `layout`, as a harness of its own
/// builds them (HeightBounds).
std::vector<glm::vec4> traceInHarness(const SurfaceTextures& textures, Technique technique,
                                      const std::vector<glm::vec4>& rays,
                                      const SourceFile& main = kHarnessMain,
                                      Accessors accessors = Accessors::Harness,
                                      const TexelShadows* texelShadows = nullptr,
                                      PyramidLayout layout = PyramidLayout::Auto) {
    const bool own = accessors == Accessors::Harness;
    HFX_CHECK(!(own && texelShadows));
    HeightBounds bounds(textures.config(), layout);
    std::vector<SourceFile> parts{kComputeHeader, surfaceShader("bindings.glsl"),
                                  {"harness_layout.comp",
                                   str("#define HFX_PYRAMID_ATLAS ", bounds.layout() == PyramidLayout::Atlas ? 1 : 0, "\n"),
                                   "test"}};
    if (texelShadows) parts.push_back({"harness_texels.comp", "#define HFX_TEXEL_SHADOWS 1\n", "test"});
    if (own) parts.push_back(kHarness);
    else parts.insert(parts.end(), {surfaceShader("surface/uniforms.glsl"), surfaceShader("surface/heights.glsl")});
    parts.insert(parts.end(), {surfaceShader("trace/common.glsl"), surfaceShader(techniqueInfo(technique).shader),
                               surfaceShader("surface/shadow.glsl"), kHarnessBuffers, main});
    const ShaderProgram p = ShaderProgram::compute(parts);
    const SurfaceTexturesConfig& config = textures.config();
    SurfaceUniforms u;
    u.setField({config.width, config.height}, config.edges);
    if (texelShadows) {
        const ShadowLight& c = texelShadows->light().value();
        u.shadowLight = {c.uvPerClimb, c.penumbra, c.slack};
    }
    const GlBuffer block = own ? GlBuffer() : GlBuffer::create();
    if (own) {
        p.set("u_wrap", wrapFlags(config.edges));
    } else {
        glNamedBufferStorage(block.id(), sizeof u, &u, 0);
        glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SURFACE, block.id());
    }
    BoundsPass().refresh(textures, bounds); // and the atlas layout's level-0 cells heights.glsl reads
    glBindTextureUnit(HFX_UNIT_SURFACE, textures.surface());
    bounds.bind(0);
    glBindTextureUnit(HFX_UNIT_TEXEL_SHADOWS, texelShadows ? texelShadows->texture() : 0);
    std::vector<glm::vec4> hits = runHarness(p, rays);
    glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SURFACE, 0);
    return hits;
}

TEST_F(TracerContract, EveryTracerRunsInAComputeHarnessAndHitsWhereTheExactIntersectionSays) {
    constexpr int N = 64;
    constexpr double depth = 0.1, angle = 60.0 * std::numbers::pi / 180.0, azimuth = 0.7;
    const auto heights = sumOfSines(N, {{0.3, 2, 1, 0.0}, {0.12, -1, 3, 0.7}});
    AccuracyProbe probe(cl(), heights, N, float(depth)); // the renderer's own textures and pyramid
    const glm::dvec3 toEye(std::sin(angle) * std::cos(azimuth), std::sin(angle) * std::sin(azimuth), std::cos(angle));
    const glm::dvec2 parallax = glm::dvec2(toEye) / toEye.z * depth;

    constexpr int kRays = 2048;
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::vec4> rays;
    std::vector<glm::dvec2> exact;
    for (int i = 0; i < kRays; ++i) {
        const glm::dvec2 uv0(unit(random), unit(random));
        const auto hit = probe.exact().traceView(uv0, toEye, depth);
        ASSERT_TRUE(hit);
        exact.push_back(hit->uv);
        rays.emplace_back(float(uv0.x), float(uv0.y), float(parallax.x), float(parallax.y));
        rays.emplace_back(float(toEye.z), 0.0f, 32.0f, 0.0f);
    }
    auto meanError = [&](const TechniqueInfo& t) {
        const std::vector<glm::vec4> hits = traceInHarness(probe.textures(), t.technique, rays);
        double sum = 0.0;
        for (int i = 0; i < kRays; ++i) sum += glm::length(glm::dvec2(hits[i].x, hits[i].y) - exact[i]) * N;
        return sum / kRays;
    };
    // Bounds after each technique's error in the fragment stage (docs/ACCURACY.md, smooth map),
    // with room: the harness must not change what a tracer computes. Normal mapping does not
    // trace (it stays at the entry, far off); offset limiting only has to beat it clearly.
    const double untraced = meanError(techniqueInfo(Technique::NormalMapping));
    EXPECT_GT(untraced, 2.0);
    for (const TechniqueInfo& t : kTechniqueTable) {
        const double error = meanError(t);
        std::printf("[harness] %-8s mean error %.4f texels\n", t.name, error);
        switch (t.technique) {
        case Technique::NormalMapping: break;
        case Technique::ParallaxOffset: EXPECT_LT(error, 0.75 * untraced) << t.name; break;
        case Technique::SteepParallax: EXPECT_LT(error, 0.5) << t.name; break; // the step size: 1/32 of the depth
        case Technique::Hierarchical: EXPECT_LT(error, 0.01) << t.name; break;
        default: EXPECT_LT(error, 0.05) << t.name; // pom, secant, relief: refined inside the bracket
        }
    }
}

/// A field built to trip a hierarchical walk: walls one texel wide at the top of the relief
/// (h = 1) every 16 texels, broad plateaus exactly at the top and at the bottom, and a slope
/// between them, 512 x 512.
std::vector<float> thinWallsAndPlateaus(int n) {
    std::vector<float> h(size_t(n) * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            float v;
            if (x < n / 4) v = 1.0f;                               // top plateau
            else if (x < n / 2) v = 0.0f;                          // bottom plateau
            else v = 0.5f + 0.3f * float(y % 64) / 64.0f;          // ramps
            if ((x % 16 == 7 && y % 32 < 24) || (y % 16 == 3 && x % 32 >= 8)) v = 1.0f; // thin walls
            h[size_t(y) * n + x] = v;
        }
    return h;
}

TEST_F(TracerContract, TheExactTracerNeverStepsOverASurfaceOnAMillionRays) {
    constexpr int N = 512;
    constexpr double depth = 0.1;
    // The field as it is (walls and plateau at 1, the polygon) and lowered to 0.8: there the walk
    // starts where the ray comes down to the field's maximum, below the polygon.
    for (const float top : {1.0f, 0.8f}) {
        auto heights = thinWallsAndPlateaus(N);
        for (float& h : heights) h *= top;
        AccuracyProbe probe(cl(), heights, N, float(depth));
        // Entry points on texel centres, on the corners the gather shares and anywhere between;
        // view angles up to 89 degrees, any azimuth (axis-aligned ones included).
        constexpr int kRays = 1 << 20;
        std::mt19937 random(11);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::vector<glm::vec4> rays;
        rays.reserve(2 * kRays);
        for (int i = 0; i < kRays; ++i) {
            glm::dvec2 uv0(unit(random), unit(random));
            if (i % 3 == 0) uv0 = (glm::floor(uv0 * double(N)) + 0.5) / double(N);
            else if (i % 3 == 1) uv0 = glm::floor(uv0 * double(N)) / double(N);
            const double angle = std::acos(unit(random)) * 89.0 / 90.0;
            const double azimuth = i % 16 == 0 ? std::numbers::pi / 2 * double(i / 16 % 4) : 2 * std::numbers::pi * unit(random);
            const glm::dvec2 parallax = glm::dvec2(std::cos(azimuth), std::sin(azimuth)) * std::tan(angle) * depth;
            rays.emplace_back(float(uv0.x), float(uv0.y), float(parallax.x), float(parallax.y));
            rays.emplace_back(float(std::cos(angle)), 0.0f, 32.0f, 0.0f);
        }
        std::vector<double> exactDepth(kRays);
        for (int i = 0; i < kRays; ++i) {
            const glm::vec4 a = rays[2 * size_t(i)];
            const auto hit = probe.exact().traceView(glm::dvec2(a.x, a.y), glm::dvec3(double(a.z) / depth, double(a.w) / depth, 1.0), depth);
            exactDepth[i] = hit ? hit->t : 1.0;
        }
        // Exact, then with a tolerance (a pixel budget's depth fraction): the hit may then stop short
        // of the exact one by up to the tolerance, never more and never past it.
        // Both pyramid layouts, each exact and with the tolerance.
        for (const auto& [layout, tolerance] : {std::pair{PyramidLayout::MipChain, 0.0f}, {PyramidLayout::MipChain, 0.01f},
                                                {PyramidLayout::Atlas, 0.0f}, {PyramidLayout::Atlas, 0.01f}}) {
            for (int i = 0; i < kRays; ++i) rays[2 * size_t(i) + 1].w = tolerance;
            // The renderer's accessors: rays run up to 5.7 texcoords, across the tile's edges.
            const std::vector<glm::vec4> hits = traceInHarness(probe.textures(), Technique::Hierarchical, rays, kHarnessMain,
                                                               Accessors::Renderer, nullptr, layout);
            int deeper = 0, off = 0, early = 0, touches = 0;
            double worst = 0.0;
            for (int i = 0; i < kRays; ++i) {
                const glm::vec4 a = rays[2 * size_t(i)];
                // In texels along the ray: how far past (or short of) the exact first hit.
                const double perDepth = glm::length(glm::dvec2(a.z, a.w)) * N;
                const double texels = (double(hits[i].z) - exactDepth[i]) * perDepth;
                const double allowed = double(tolerance) * perDepth; // how far short it may stop
                early += texels < -0.05 && -texels <= allowed + 0.05;
                // A ray that passes a ridge's or an edge's top within the shader's rounding (its
                // float position times the slope there: 1e-4 of the relief) touches it in float and
                // misses it in double: a stop short on the surface there is no error. On the
                // lowered field a few rays of a million graze a wall's top so (3 of them here).
                if (texels < -allowed - 0.05) {
                    const double t = double(hits[i].z);
                    const glm::dvec2 at = glm::dvec2(a.x, a.y) - glm::dvec2(a.z, a.w) * t;
                    if (probe.exact().heightAt(at) - (1.0 - t) > -1e-4) {
                        ++touches;
                        continue;
                    }
                }
                if (texels > 0.05 || -texels > allowed + 0.05) {
                    if (off < 8) // the first few, to reproduce (negative: the tracer stopped short)
                        std::printf("[off] tolerance %g, uv (%.9g, %.9g) parallax (%.9g, %.9g): %.4f vs exact %.4f (%.2f texels)\n",
                                    tolerance, a.x, a.y, a.z, a.w, hits[i].z, exactDepth[i], texels);
                    ++off;
                    deeper += texels > 0.0;
                }
                worst = std::max(worst, std::abs(texels) - (texels < 0.0 ? allowed : 0.0));
            }
            std::printf("[tunnel] top %g, tolerance %g, %s: %d of %d rays deeper than the exact hit, %d off by > "
                        "0.05 texel beyond the tolerance (worst %.3f texels), %d stopped short within it, %d on a top they graze\n",
                        top, tolerance, layoutName(layout), deeper, kRays, off, worst, early, touches);
            EXPECT_EQ(deeper, 0) << "top " << top << ", tolerance " << tolerance << ", " << layoutName(layout);
            EXPECT_EQ(off, 0) << "top " << top << ", tolerance " << tolerance << ", " << layoutName(layout);
            EXPECT_LT(touches, kRays / 10000) << "top " << top << ", tolerance " << tolerance << ", " << layoutName(layout);
            if (tolerance > 0.0f) {
                EXPECT_GT(early, kRays / 100) << "the tolerance was not used";
            }
        }
    }
}

/// The fragment stage's texcoords carry an ulp or two of rounding. A ray entering on a plateau's top
/// (h = 1) at a sample where the surface falls away touches the top at its entry; moved by that
/// rounding off the plateau it passes a hair above the falling patch, and a walk that takes this
/// as a miss goes on down to the floor (seen on a GPU: 0.04-0.07% of a brick map's pixels).
TEST_F(TracerContract, ATouchWithinRoundingAtAPlateausTopIsAHit) {
    constexpr int N = 256, lo = 96, hi = 160; // the plateau: texels [lo, hi) on both axes at h = 1
    constexpr double depth = 0.1;
    std::vector<float> heights(size_t(N) * N, 0.25f);
    for (int y = lo; y < hi; ++y)
        for (int x = lo; x < hi; ++x) heights[size_t(y) * N + x] = 1.0f;
    AccuracyProbe probe(cl(), heights, N, float(depth));
    // Entries on the texel centres of the plateau's edges and corners, moved by -2..2 ulps of
    // their texcoords (HFX_TOUCH_ULPS); rays at 80-85 degrees leaving the plateau over that edge.
    std::vector<glm::vec4> rays;
    for (int k = lo; k < hi; ++k)
        for (const auto& [texel, outward] : {std::pair{glm::ivec2(lo, k), glm::dvec2(-1, 0)}, std::pair{glm::ivec2(hi - 1, k), glm::dvec2(1, 0)},
                                             std::pair{glm::ivec2(k, lo), glm::dvec2(0, -1)}, std::pair{glm::ivec2(k, hi - 1), glm::dvec2(0, 1)}})
            for (int ulps = -2; ulps <= 2; ++ulps)
                for (const double angle : {80.0, 82.5, 85.0})
                    for (const double turn : {-0.6, 0.0, 0.6}) {
                        glm::vec2 uv = (glm::vec2(texel) + 0.5f) / float(N);
                        for (int i = 0; i < std::abs(ulps); ++i) {
                            uv.x = std::nextafter(uv.x, ulps > 0 ? 1.0f : 0.0f);
                            uv.y = std::nextafter(uv.y, ulps > 0 ? 1.0f : 0.0f);
                        }
                        const glm::dvec2 away(std::cos(turn) * outward.x - std::sin(turn) * outward.y,
                                                    std::sin(turn) * outward.x + std::cos(turn) * outward.y); // the ray moves -parallax
                        const glm::dvec2 parallax = -away * std::tan(angle * std::numbers::pi / 180.0) * depth;
                        rays.emplace_back(uv.x, uv.y, float(parallax.x), float(parallax.y));
                        rays.emplace_back(float(std::cos(angle * std::numbers::pi / 180.0)), 0.0f, 32.0f, 0.0f);
                    }
    for (const PyramidLayout layout : kLayouts) {
        const std::vector<glm::vec4> hits = traceInHarness(probe.textures(), Technique::Hierarchical, rays, kHarnessMain,
                                                           Accessors::Renderer, nullptr, layout);
        int walkedOn = 0;
        double deepest = 0.0;
        for (size_t i = 0; i < hits.size(); ++i) {
            deepest = std::max(deepest, double(hits[i].z));
            if (hits[i].z > 1e-3f && walkedOn++ < 4)
                std::printf("[touch] uv (%.9g, %.9g) parallax (%.6g, %.6g): depth %.4f\n", rays[2 * i].x, rays[2 * i].y,
                            rays[2 * i].z, rays[2 * i].w, hits[i].z);
        }
        std::printf("[touch] %s: %d of %zu entries on the plateau's edge walked on (deepest hit %.2g)\n",
                    layoutName(layout), walkedOn, hits.size(), deepest);
        EXPECT_EQ(walkedOn, 0) << layoutName(layout);
    }
}

TEST_F(TracerContract, TheExactShadowNeverMissesABlockerOnAMillionRays) {
    // Light rays from points on the same field of thin walls and plateaus, any azimuth, up to 85
    // degrees from the normal, with a sharpness so high that the penumbra vanishes: the exact
    // tracer's hfx_shadow is 1 exactly where the exact CPU ray meets the surface.
    constexpr int N = 512;
    constexpr double depth = 0.1;
    const auto heights = thinWallsAndPlateaus(N);
    AccuracyProbe probe(cl(), heights, N, float(depth));
    constexpr int kRays = 1 << 20;
    std::mt19937 random(12);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::vec4> rays;
    std::vector<glm::dvec3> origins, directions;
    rays.reserve(2 * kRays);
    while (origins.size() < size_t(kRays)) {
        glm::dvec2 uv(unit(random), unit(random));
        if (origins.size() % 3 == 0) uv = (glm::floor(uv * double(N)) + 0.5) / double(N);
        const double h0 = probe.exact().heightAt(uv);
        if (h0 > 0.999) continue; // on top: nothing can be above (the shader does not ask)
        const double angle = std::acos(unit(random)) * 85.0 / 90.0;
        const double azimuth = origins.size() % 16 == 0 ? std::numbers::pi / 2 * double(origins.size() / 16 % 4)
                                                        : 2 * std::numbers::pi * unit(random);
        // Per unit of height climbed the light ray moves tan(angle) * depth in texcoords.
        const glm::dvec3 direction(std::cos(azimuth) * std::tan(angle) * depth,
                                   std::sin(azimuth) * std::tan(angle) * depth, 1.0);
        const glm::dvec2 span = glm::dvec2(direction) * (1.0 - h0);
        rays.emplace_back(float(uv.x), float(uv.y), float(span.x), float(span.y));
        rays.emplace_back(float(h0), 0.0f, 8.0f, 1e6f);
        origins.emplace_back(uv, h0);
        directions.push_back(direction);
    }
    for (const PyramidLayout layout : kLayouts) {
        const std::vector<glm::vec4> shadow = traceInHarness(probe.textures(), Technique::Hierarchical, rays, kShadowMain,
                                                             Accessors::Renderer, nullptr, layout);
        int missed = 0, invented = 0, blocked = 0, grazing = 0;
        for (int i = 0; i < kRays; ++i) {
            const glm::dvec3 o = origins[size_t(i)], d = directions[size_t(i)];
            const double tMax = 1.0 - o.z;
            // Clearly blocked: the ray raised by 2e-3 of the depth still meets the surface. Clear:
            // the ray itself (from just above the point) meets nothing.
            const bool deep = probe.exact().intersect(o + glm::dvec3(0, 0, 2e-3), d, tMax).has_value();
            const bool touches = probe.exact().intersect(o + glm::dvec3(0, 0, 1e-7), d, tMax).has_value();
            const bool dark = shadow[size_t(i)].x >= 1.0f;
            blocked += deep;
            grazing += touches && !deep;
            if (deep && !dark) {
                if (missed < 8)
                    std::printf("[missed] uv (%.9g, %.9g) h0 %.6f span (%.6g, %.6g): shadow %.4f\n", o.x, o.y, o.z,
                                rays[2 * size_t(i)].z, rays[2 * size_t(i)].w, shadow[size_t(i)].x);
                ++missed;
            }
            if (!touches && dark) {
                if (invented < 8)
                    std::printf("[invented] uv (%.9g, %.9g) h0 %.6f span (%.6g, %.6g) %.6f\n", o.x, o.y, o.z,
                                rays[2 * size_t(i)].z, rays[2 * size_t(i)].w, shadow[size_t(i)].x);
                ++invented;
            }
        }
        std::printf("[shadow] %s: %d of %d rays blocked, %d grazing; %d blockers missed, %d invented\n", layoutName(layout),
                    blocked, kRays, grazing, missed, invented);
        EXPECT_GT(blocked, kRays / 10);
        EXPECT_EQ(missed, 0) << layoutName(layout);
        EXPECT_EQ(invented, 0) << layoutName(layout);
    }
}

TEST_F(TracerContract, AGrazeWithinTheShadowToleranceDoesNotHideABlockerFurtherOn) {
    // A light ray along a row of a flat field at 0.9, rising 5e-4 per texel: two texels on, a
    // ridge stands 5e-5 above it (within HFX_SHADOW_EPSILON: not a blocker, but a clearance ratio
    // below 0, -0.05), a hundred texels on a wall stands 1e-3 above it. The walk must still open
    // the wall's cell: a negative ratio would lift the cone edge above the ray itself (by 0.05 of
    // its climb: 2.5e-3 at the wall) and skip it, returning a penumbra for a hard shadow.
    constexpr int N = 256, x0 = 10, y0 = 40;
    constexpr float h0 = 0.9f, perTexel = 5e-4f;
    std::vector<float> heights(size_t(N) * N, h0);
    for (int y = y0 - 1; y <= y0 + 1; ++y) {
        heights[size_t(y) * N + x0 + 2] = h0 + 2 * perTexel + 5e-5f;
        heights[size_t(y) * N + x0 + 100] = h0 + 100 * perTexel + 1e-3f;
    }
    AccuracyProbe probe(cl(), heights, N, 0.1f);
    const glm::vec2 uv = (glm::vec2(x0, y0) + 0.5f) / float(N);
    const float climb = 1.0f - h0, texels = climb / perTexel; // the span: 200 texels over the climb
    // The exact CPU ray meets the wall (and the ridge only within the tolerance).
    const glm::dvec3 o(uv, h0), d(double(texels) / N / climb, 0.0, 1.0); // texcoords per unit of climb
    ASSERT_TRUE(probe.exact().intersect(o + glm::dvec3(0, 0, 2e-4), d, 1.0 - h0).has_value());
    std::vector<glm::vec4> rays;
    for (const float sharpness : {2.0f, 8.0f, 1e6f}) {
        rays.emplace_back(uv.x, uv.y, texels / float(N), 0.0f);
        rays.emplace_back(h0, 0.0f, 8.0f, sharpness);
    }
    const std::vector<glm::vec4> shadow =
        traceInHarness(probe.textures(), Technique::Hierarchical, rays, kShadowMain, Accessors::Renderer);
    for (size_t i = 0; i < shadow.size(); ++i) EXPECT_EQ(shadow[i].x, 1.0f) << "ray " << i;
    // Without the wall the ray is lit: the ridge alone must not shadow it.
    heights[size_t(y0) * N + x0 + 100] = heights[size_t(y0 - 1) * N + x0 + 100] = heights[size_t(y0 + 1) * N + x0 + 100] = h0;
    AccuracyProbe open(cl(), heights, N, 0.1f);
    for (const glm::vec4& s : traceInHarness(open.textures(), Technique::Hierarchical, rays, kShadowMain, Accessors::Renderer))
        EXPECT_LT(s.x, 1.0f);
}

/// The fields the shadow walk's shortcuts are held on: one-texel walls and plateaus (hard
/// shadows, blockers finer than a texel) and a smooth sum of sines (long penumbrae).
struct ShadowField {
    const char* name;
    std::vector<float> heights;
};
std::vector<ShadowField> shadowFields(int n) {
    return {{"walls", thinWallsAndPlateaus(n)},
            {"sines", sumOfSines(n, {{0.3, 3, 1, 0.0}, {0.12, -4, 7, 0.7}, {0.05, 11, -9, 0.3}})}};
}

/// A shadow read from the texel shadows against the walk's, ray by ray (x of each harness
/// result, fetches in y), over the rays `skip` does not mark: the rays the walk puts in hard
/// shadow, those whose hard shadow differs, and over the rest that both leave out of it the
/// penumbra's mean and worst difference; the reads' fetches summed.
struct ShadowTally {
    int hard = 0, hardDiffer = 0, soft = 0;
    double error = 0, worst = 0, fetches = 0;
};
ShadowTally tallyShadows(const std::vector<glm::vec4>& walked, const std::vector<glm::vec4>& read,
                         const std::vector<bool>& skip = {}) {
    ShadowTally t;
    for (size_t i = 0; i < walked.size(); ++i) {
        if (i < skip.size() && skip[i]) continue;
        const float a = walked[i].x, b = read[i].x;
        t.hard += a == 1.0f;
        t.fetches += read[i].y;
        if ((a == 1.0f) != (b == 1.0f)) {
            ++t.hardDiffer;
        } else if (a < 1.0f) {
            ++t.soft;
            t.error += std::abs(a - b);
            t.worst = std::max(t.worst, double(std::abs(a - b)));
        }
    }
    t.error /= std::max(t.soft, 1);
    return t;
}

TEST_F(TracerContract, TexelShadowsAreTheWalkAtEverySampleAndStandInForItWhereTheHardShadowAgrees) {
    // The texel shadows (TexelShadowPass) must hold the exact walk's shadow at every sample of
    // the field, drawn by the frame's own path; and a ray of their light that reads them must
    // come out as its walk does: the same hard shadow, except where that changes inside a cell
    // between samples that agree (a sliver finer than the samples: counted and bounded), the
    // penumbra blended within a bound, in fewer fetches. Texels one sample off must fail the
    // bounds (else the comparison could not fail). At every second sample (the stride a pixel
    // budget picks where texels are smaller than pixels) the smooth field keeps those bounds; on
    // the one-texel walls the shadows finer than two samples are missed between them (measured:
    // 2.7-3.0% of the rays, their penumbra off by 0.003 on average): at most 3.5%.
    constexpr int N = 256;
    constexpr float depth = 0.1f;
    const std::vector<ShadowField> fields = shadowFields(N);
    const glm::vec3 lights[] = {{0.6f, 0.55f, 0.3f}, {-0.2f, 0.3f, -0.9f}};
    constexpr int kRays = 1 << 18;
    TexelShadowPass pass;
    HeightBounds bounds(N, N, EdgeMode::Wrap);
    for (const ShadowField& field : fields) {
        StaticField source(cl(), N, N, EdgeMode::Wrap, field.heights);
        // Float32 texels, every effect's on a CPU rasteriser: the walks read the heights the exact
        // CPU intersection reads (a GPU's float16 rounds them).
        SurfacePipeline surface(
            cl(), SurfacePipelineConfig::of(source, depth, {.mipmaps = false, .format = SurfaceFormat::Float32}));
        const HeightFieldTracer exact(field.heights, N, N, EdgeMode::Wrap);
        for (size_t li = 0; li < std::size(lights); ++li) {
            for (const auto& [sharpness, stride] : {std::pair{2.0f, 1}, std::pair{8.0f, 1}, std::pair{2.0f, 2}, std::pair{8.0f, 2}}) {
                const int M = N / stride; // texel-shadow samples per edge
                DirectionalLight light;
                light.direction = lights[li];
                const std::optional<ShadowLight> c = flatSurfaceLight(
                    SurfaceFrame::ofPlane({}), light, {.depthScale = depth, .shadowSharpness = sharpness});
                ASSERT_TRUE(c);
                surface.run(source.buffer());
                const SurfaceTextures& textures = surface.textures();
                TexelShadows shadows;
                pass.draw(textures, bounds, *c, stride, shadows);
                ASSERT_NE(shadows.texture(), 0u);
                std::vector<float> texels(size_t(M) * M);
                glGetTextureImage(shadows.texture(), 0, GL_RED, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                                  texels.data());
                const auto walk = [&](const std::vector<glm::vec4>& r, bool read) {
                    return traceInHarness(textures, Technique::Hierarchical, r, kShadowMain, Accessors::Renderer,
                                          read ? &shadows : nullptr);
                };
                const auto rayFrom = [&, sharpness = sharpness](std::vector<glm::vec4>& r, glm::vec2 uv, float h0) {
                    const glm::vec2 span = c->uvPerClimb * (1.0f - h0);
                    r.emplace_back(uv.x, uv.y, span.x, span.y);
                    r.emplace_back(h0, 0.0f, 8.0f, sharpness);
                };
                // Every sample: the walk from it, as the pass ran it.
                std::vector<glm::vec4> sampleRays;
                std::vector<size_t> sampleOf;
                for (int j = 0; j < M; ++j)
                    for (int i = 0; i < M; ++i) {
                        const float h0 = field.heights[size_t(j * stride) * N + size_t(i * stride)];
                        if (h0 >= 1.0f) continue;
                        rayFrom(sampleRays, (glm::vec2(i, j) * float(stride) + 0.5f) / float(N), h0);
                        sampleOf.push_back(size_t(j) * M + size_t(i));
                    }
                const std::vector<glm::vec4> atSamples = walk(sampleRays, false);
                double worst = 0;
                for (size_t k = 0; k < sampleOf.size(); ++k)
                    worst = std::max(worst, double(std::abs(atSamples[k].x - texels[sampleOf[k]])));
                EXPECT_LE(worst, 1e-5) << field.name << " light " << li << " sharpness " << sharpness;

                // Anywhere: the walk against the ray that reads the texels.
                std::mt19937 random(31 + unsigned(li));
                std::uniform_real_distribution<double> unit(0.0, 1.0);
                std::vector<glm::vec4> rays;
                while (rays.size() < 2 * size_t(kRays)) {
                    const glm::dvec2 uv(unit(random), unit(random));
                    const double h0 = exact.heightAt(uv);
                    if (h0 < 0.999) rayFrom(rays, glm::vec2(uv), float(h0));
                }
                const std::vector<glm::vec4> walked = walk(rays, false);
                const auto compare = [&](const std::vector<glm::vec4>& read) { return tallyShadows(walked, read); };
                const ShadowTally t = compare(walk(rays, true));
                double fetchesWalked = 0;
                for (int i = 0; i < kRays; ++i) fetchesWalked += walked[size_t(i)].y;
                std::printf("[texels] %s light %zu sharpness %.0f stride %d: %d of %d rays in hard shadow, %d differ there; "
                            "penumbra off by %.4f on average, %.3f at most; fetches %.2f -> %.2f per ray\n",
                            field.name, li, sharpness, stride, t.hard, kRays, t.hardDiffer, t.error, t.worst,
                            fetchesWalked / kRays, t.fetches / kRays);
                EXPECT_GT(t.hard, kRays / 50) << field.name;
                const bool finerThanSamples = stride > 1 && std::string(field.name) == "walls";
                const int hardBound = finerThanSamples ? kRays * 35 / 1000 : kRays / 1000;
                const double worstBound = finerThanSamples ? 1.0 : 0.3;
                EXPECT_LE(t.hardDiffer, hardBound) << field.name << " light " << li << " sharpness " << sharpness << " stride " << stride;
                // The blend is used where the four samples differ by at most 0.25 (HFX_TEXEL_SPREAD).
                EXPECT_LE(t.error, 0.005) << field.name << " light " << li << " sharpness " << sharpness << " stride " << stride;
                EXPECT_LE(t.worst, worstBound) << field.name << " light " << li << " sharpness " << sharpness << " stride " << stride;
                EXPECT_LT(t.fetches, 0.8 * fetchesWalked) << field.name << " light " << li;

                // The texels one sample off along u: the same comparison must fail.
                std::vector<float> shifted(texels.size());
                for (int j = 0; j < M; ++j)
                    for (int i = 0; i < M; ++i)
                        shifted[size_t(j) * M + size_t(i)] = texels[size_t(j) * M + size_t((i + 1) % M)];
                glTextureSubImage2D(shadows.texture(), 0, 0, 0, M, M, GL_RED, GL_FLOAT, shifted.data());
                const ShadowTally off = compare(walk(rays, true));
                std::printf("[texels] ... one sample off: %d differ in hard shadow, penumbra off by %.4f on average, "
                            "%.3f at most\n", off.hardDiffer, off.error, off.worst);
                EXPECT_TRUE(off.hardDiffer > hardBound || off.error > 0.005 || off.worst > worstBound)
                    << field.name << " light " << li << ": shifted texels pass (" << off.hardDiffer << " differ, "
                    << off.error << " penumbra error)";
            }
        }
    }
}

TEST_F(TracerContract, TexelShadowsAtAStrideWalkPastTheLastSampleOfAClampedEdge) {
    // A field that clamps at its edges, texel shadows at every second sample: between the last
    // sample they hold and the field's edge the relief goes on, and nothing brackets a point
    // there (a gather would clamp to the last sample's shadow twice). Those points must walk:
    // their shadow is the walk's, to the bit. Elsewhere the smooth field keeps the usual bounds.
    constexpr int N = 128, stride = 2;
    const std::vector<float> heights = sumOfSines(N, {{0.3, 3, 1, 0.0}, {0.12, -4, 7, 0.7}, {0.05, 11, -9, 0.3}});
    StaticField source(cl(), N, N, EdgeMode::Clamp, heights);
    // Float32 texels: the walks read the heights the exact CPU intersection reads.
    SurfacePipeline surface(
        cl(), SurfacePipelineConfig::of(source, 0.1f, {.mipmaps = false, .format = SurfaceFormat::Float32}));
    const HeightFieldTracer exact(heights, N, N, EdgeMode::Clamp);
    DirectionalLight light;
    light.direction = {0.6f, 0.35f, 0.3f}; // towards +u, +v: the rays from the far strips cross the field
    const std::optional<ShadowLight> c =
        flatSurfaceLight(SurfaceFrame::ofPlane({}), light, {.depthScale = 0.1f, .shadowSharpness = 2.0f});
    ASSERT_TRUE(c);
    surface.run(source.buffer());
    TexelShadowPass pass;
    TexelShadows shadows;
    HeightBounds bounds(surface.textures().config());
    pass.draw(surface.textures(), bounds, *c, stride, shadows);
    ASSERT_EQ(shadows.stride(), stride);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::vec4> rays;
    std::vector<bool> inStrip;
    while (inStrip.size() < 65536) {
        glm::dvec2 uv(unit(random), unit(random));
        // Half of them in the strips past the last held sample (N - stride) along u or v.
        if (inStrip.size() % 2 == 0) (inStrip.size() % 4 == 0 ? uv.x : uv.y) = (N - stride + 0.5 + 1.5 * unit(random)) / N;
        const double h0 = exact.heightAt(uv);
        if (h0 >= 0.999) continue;
        const glm::vec2 span = c->uvPerClimb * float(1.0 - h0);
        rays.emplace_back(float(uv.x), float(uv.y), span.x, span.y);
        rays.emplace_back(float(h0), 0.0f, 8.0f, 2.0f);
        const glm::dvec2 cell = uv * double(N) - 0.5;
        inStrip.push_back(cell.x >= N - stride || cell.y >= N - stride);
    }
    const auto trace = [&](bool read) {
        return traceInHarness(surface.textures(), Technique::Hierarchical, rays, kShadowMain,
                              Accessors::Renderer, read ? &shadows : nullptr);
    };
    const std::vector<glm::vec4> walked = trace(false), read = trace(true);
    int strip = 0, stripDiffer = 0;
    for (size_t i = 0; i < inStrip.size(); ++i) {
        strip += inStrip[i];
        stripDiffer += inStrip[i] && walked[i].x != read[i].x;
    }
    const ShadowTally elsewhere = tallyShadows(walked, read, inStrip);
    std::printf("[texels clamped] %d rays in the strips, %d differ from the walk; elsewhere %d differ in hard shadow, "
                "penumbra off by %.4f on average\n", strip, stripDiffer, elsewhere.hardDiffer, elsewhere.error);
    EXPECT_GT(strip, 16000);
    EXPECT_EQ(stripDiffer, 0);
    EXPECT_LE(elsewhere.hardDiffer, int(inStrip.size()) / 1000);
    EXPECT_LE(elsewhere.error, 0.005);
}

/// The renderer's pyramid read (surface/heights.glsl, hfx_bounds) in a compute harness: per item
/// (a: cell, level) the bounds it returns.
const SourceFile kPyramidReadMain{"harness_pyramid.comp", R"(
void main() {
    uint i;
    vec4 a, b;
    if (!hfx_harness_ray(i, a, b)) return;
    hits[i] = vec4(hfx_bounds(ivec2(a.xy), int(a.z)), 0.0, 0.0);
}
)",
                                  "test"};

TEST_F(TracerContract, TheRenderersPyramidReadFindsEveryLevelInItsImageOnSquareAndOblongFields) {
    // Every level lies inside the atlas image and apart from the others (HeightBounds::
    // atlasOrigin), and heights.glsl's read of a level's cell, wrapped from anywhere, is
    // the CPU pyramid's in either layout (the atlas, the mip chain): fields wider than tall,
    // taller than wide, square, and one row high.
    std::mt19937 random(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (const auto& [W, H] : {std::pair{64, 16}, std::pair{16, 64}, std::pair{32, 32}, std::pair{128, 2}, std::pair{4, 256}}) {
        const auto [atlasW, atlasH] = HeightBounds::atlasSize(W, H);
        const int levels = int(std::bit_width(unsigned(std::max(W, H))));
        std::vector<glm::ivec4> rects; // x, y, width, height
        for (int level = 0; level < levels; ++level) {
            const auto [x, y] = HeightBounds::atlasOrigin(W, H, level);
            const glm::ivec4 r(x, y, std::max(W >> level, 1), std::max(H >> level, 1));
            EXPECT_TRUE(r.x >= 0 && r.y >= 0 && r.x + r.z <= atlasW && r.y + r.w <= atlasH)
                << W << "x" << H << " level " << level << " at " << r.x << "," << r.y << " outside " << atlasW << "x" << atlasH;
            for (const glm::ivec4& o : rects)
                EXPECT_FALSE(r.x < o.x + o.z && o.x < r.x + r.z && r.y < o.y + o.w && o.y < r.y + r.w)
                    << W << "x" << H << " level " << level << " overlaps an earlier level";
            rects.push_back(r);
        }
        std::vector<float> heights(size_t(W) * H);
        for (float& h : heights) h = unit(random);
        StaticField field(cl(), W, H, EdgeMode::Wrap, heights);
        for (const PyramidLayout layout : {PyramidLayout::Atlas, PyramidLayout::MipChain}) {
        // Float32 texels: the pyramid of the heights themselves.
        SurfacePipeline surface(
            cl(), SurfacePipelineConfig::of(field, 0.05f, {.mipmaps = false, .format = SurfaceFormat::Float32}));
        surface.run(field.buffer());
        const std::vector<float> reference = pyramidReference(heights, W, H);
        std::vector<glm::vec4> items;
        std::vector<glm::vec2> expected;
        size_t offset = 0;
        for (int level = 0; level < levels; ++level) {
            const int w = std::max(W >> level, 1), h = std::max(H >> level, 1);
            for (int k = 0; k < 64; ++k) {
                const glm::ivec2 cell(int(unit(random) * 3 * w) - w, int(unit(random) * 3 * h) - h); // [-w, 2w)
                const size_t at = offset + size_t((cell.y % h + h) % h) * w + size_t((cell.x % w + w) % w);
                items.emplace_back(float(cell.x), float(cell.y), float(level), 0.0f);
                items.emplace_back(0.0f);
                expected.emplace_back(reference[2 * at], reference[2 * at + 1]);
            }
            offset += size_t(w) * h;
        }
        const std::vector<glm::vec4> read = traceInHarness(surface.textures(), Technique::Hierarchical, items, kPyramidReadMain,
                                                           Accessors::Renderer, nullptr, layout);
        int wrong = 0;
        for (size_t i = 0; i < read.size(); ++i) wrong += glm::vec2(read[i]) != expected[i];
        EXPECT_EQ(wrong, 0) << W << "x" << H << (layout == PyramidLayout::Atlas ? ", atlas: " : ", mip chain: ") << wrong
                            << " of " << read.size() << " reads are not the pyramid's";
        }
    }
}

/// The renderer's cell samples (surface/heights.glsl, hfx_cell_samples) in a compute harness: per
/// item (a: cell) the four samples.
const SourceFile kCellReadMain{"harness_cells.comp", R"(
void main() {
    uint i;
    vec4 a, b;
    if (!hfx_harness_ray(i, a, b)) return;
    hits[i] = hfx_cell_samples(ivec2(a.xy));
}
)",
                               "test"};

TEST_F(TracerContract, TheCellsHoldTheSamplesAGatherReadsAndFollowEveryUpload) {
    // The exact tracer's patch solve reads a cell's four samples: in the atlas layout from the
    // cells image (BoundsPass), in the mip-chain layout by a gather of the texels. Either must be
    // the stored texels around the cell's centre (half floats as stored, the far corners across
    // an edge wrapped or clamped, cells beyond the field wrapped or clamped as the pyramid's
    // level 0 is), and in the atlas an upload must make the cells stale until the next refresh
    // rebuilds them.
    constexpr int W = 64, H = 16;
    std::mt19937 random(29);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (const SurfaceFormat format : {SurfaceFormat::Float32, SurfaceFormat::Float16})
        for (const EdgeMode edges : kEdgeModes) {
            std::vector<float> first(size_t(W) * H), second(size_t(W) * H);
            for (float& h : first) h = unit(random);
            for (float& h : second) h = unit(random);
            StaticField a(cl(), W, H, edges, first), b(cl(), W, H, edges, second);
            SurfacePipeline surface(cl(), SurfacePipelineConfig::of(a, 0.05f, {.mipmaps = false, .format = format}));
            SurfacePipeline gathered(cl(), SurfacePipelineConfig::of(a, 0.05f, {.mipmaps = false, .format = format}));
            BoundsPass cells;
            HeightBounds atlas(surface.textures().config(), PyramidLayout::Atlas);
            // Cells from beyond the field on every side: [-W, 2W) x [-H, 2H).
            std::vector<glm::vec4> items;
            std::vector<glm::ivec2> cellsAsked;
            for (int k = 0; k < 4096; ++k) {
                const glm::ivec2 c(int(unit(random) * 3 * W) - W, int(unit(random) * 3 * H) - H);
                cellsAsked.push_back(c);
                items.emplace_back(float(c.x), float(c.y), 0.0f, 0.0f);
                items.emplace_back(0.0f);
            }
            auto check = [&](const char* which) {
                std::vector<glm::vec4> texels(size_t(W) * H), read(size_t(W) * H);
                const SurfaceTextures& textures = surface.textures();
                glGetTextureImage(textures.surface(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(glm::vec4)), texels.data());
                glGetTextureImage(atlas.cells(), 0, GL_RGBA, GL_FLOAT, GLsizei(read.size() * sizeof(glm::vec4)), read.data());
                auto h = [&](int i, int j) {
                    i = wrapsU(edges) ? i % W : std::min(i, W - 1);
                    j = wrapsV(edges) ? j % H : std::min(j, H - 1);
                    return texels[size_t(j) * W + size_t(i)].w;
                };
                auto samples = [&](glm::ivec2 c) { // the cell wrapped or clamped first, as level 0 is
                    const int i = wrapsU(edges) ? (c.x % W + W) % W : std::clamp(c.x, 0, W - 1);
                    const int j = wrapsV(edges) ? (c.y % H + H) % H : std::clamp(c.y, 0, H - 1);
                    return glm::vec4(h(i, j + 1), h(i + 1, j + 1), h(i + 1, j), h(i, j));
                };
                int wrong = 0;
                for (int j = 0; j < H; ++j)
                    for (int i = 0; i < W; ++i) wrong += read[size_t(j) * W + size_t(i)] != samples({i, j});
                EXPECT_EQ(wrong, 0) << surfaceFormatName(format) << ", " << edgeModeName(edges) << ", " << which << ": "
                                    << wrong << " of " << W * H << " cells";
                // heights.glsl's read in both layouts, from anywhere.
                for (const SurfacePipeline* s : {&surface, &gathered}) {
                    const std::vector<glm::vec4> got =
                        traceInHarness(s->textures(), Technique::Hierarchical, items, kCellReadMain,
                                       Accessors::Renderer, nullptr,
                                       s == &surface ? PyramidLayout::Atlas : PyramidLayout::MipChain);
                    int off = 0;
                    for (size_t k = 0; k < got.size(); ++k) off += got[k] != samples(cellsAsked[k]);
                    EXPECT_EQ(off, 0) << surfaceFormatName(format) << ", " << edgeModeName(edges) << ", " << which
                                      << (s == &surface ? ", atlas" : ", gathered") << ": " << off << " of " << got.size()
                                      << " cells read otherwise";
                }
            };
            surface.run(a.buffer());
            gathered.run(a.buffer());
            EXPECT_FALSE(atlas.cellsHold(surface.textures()));
            cells.refresh(surface.textures(), atlas);
            EXPECT_TRUE(atlas.cellsHold(surface.textures()));
            check("first heights");
            surface.run(b.buffer());
            surface.run(b.buffer()); // both of the pipeline's texture pairs
            gathered.run(b.buffer());
            gathered.run(b.buffer());
            EXPECT_FALSE(atlas.cellsHold(surface.textures())) << "an upload must leave the cells stale";
            cells.refresh(surface.textures(), atlas);
            check("second heights");
        }
}

/// The searches' bounds (surface/heights.glsl, hfx_segment_bounds) in a compute harness: per
/// segment (a: from, to; b: level) the bounds, and how far any height the search reads along it
/// (65 points, ends included) stands above their maximum or below their minimum.
const SourceFile kBoundsMain{"harness_bounds.comp", R"(
void main() {
    uint i;
    vec4 a, b;
    if (!hfx_harness_ray(i, a, b)) return;
    const vec2 bounds = hfx_segment_bounds(a.xy, a.zw, b.x);
    float above = -1.0, below = -1.0;
    for (int k = 0; k <= 64; ++k) {
        const float h = hfx_height(mix(a.xy, a.zw, float(k) / 64.0), b.x);
        above = max(above, h - bounds.x);
        below = max(below, bounds.y - h);
    }
    hits[i] = vec4(above, below, bounds);
}
)",
                              "test"};

TEST_F(TracerContract, TheSearchBoundsHoldEveryHeightTheSearchReadsOnItsSegment) {
    // Lone spikes and pits on a flat field (a mip texel near one, and only it, leaves the flat
    // height: bounds that miss the spike's reach fail) and smooth sines; a 64^2 layer and a 32^2
    // one repeated 2.7 times (a fractional mip offset), mipmapped, wrapping or clamped.
    constexpr int N = 64;
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> noise(size_t(N) * N, 0.5f);
    for (float& h : noise)
        if (const float r = unit(random); r < 0.01f) h = r < 0.005f ? 1.0f : 0.0f;
    const auto smooth = sumOfSines(N / 2, {{0.3, 1, 2, 0.8}, {0.12, 3, -2, 0.1}});
    for (const PyramidLayout layout : {PyramidLayout::Atlas, PyramidLayout::MipChain})
    for (const EdgeMode edges : {EdgeMode::Wrap, EdgeMode::Clamp}) {
        const SurfaceOptions options{.mipmaps = true};
        StaticField fieldA(cl(), N, N, edges, noise), fieldB(cl(), N / 2, N / 2, EdgeMode::Wrap, smooth);
        SurfacePipeline a(cl(), SurfacePipelineConfig::of(fieldA, 0.05f, options));
        SurfacePipeline b(cl(), SurfacePipelineConfig::of(fieldB, 0.05f, options));
        a.run(fieldA.buffer());
        b.run(fieldB.buffer());
        const int layers = edges == EdgeMode::Wrap ? 2 : 1; // layers tile: only one clamps
        const float scaleB = 2.7f;
        SurfaceUniforms u{
            .untracedHeight = 0.0f,
            .layerScale = {1.0f, scaleB, 1.0f, 1.0f},
            .layerWeight =
                layers == 2 ? glm::vec4(0.6f, 0.4f, 0.0f, 0.0f) : glm::vec4(1.0f, 0.0f, 0.0f, 0.0f),
            .layerLevel = {0.0f, std::log2(scaleB * float(N / 2) / float(N)), 0.0f, 0.0f}};
        u.setField({N, N}, edges);
        GlBuffer block = GlBuffer::create();
        glNamedBufferStorage(block.id(), sizeof u, &u, 0);
        // Segments of every length up to half the field, from anywhere (beyond [0, 1] too), at
        // mip levels 0..3, halves of levels included.
        constexpr int kSegments = 20000;
        std::vector<glm::vec4> segments;
        for (int i = 0; i < kSegments; ++i) {
            const glm::vec2 from(unit(random) * 3.0f - 1.0f, unit(random) * 3.0f - 1.0f);
            const float length = 0.5f * unit(random) * unit(random), angle = 6.2831853f * unit(random);
            segments.emplace_back(from, from + length * glm::vec2(std::cos(angle), std::sin(angle)));
            segments.emplace_back(float(i % 7) * 0.5f, 0.0f, 0.0f, 0.0f);
        }
        const ShaderProgram p = ShaderProgram::compute(
            {kComputeHeader, surfaceShader("bindings.glsl"), surfaceShader("surface/uniforms.glsl"),
             surfaceShader("surface/heights.glsl"), kHarnessBuffers,
             kBoundsMain},
            {{"HFX_LAYERS", std::to_string(layers)},
             {"HFX_BOUNDED_SEARCH", "1"},
             {"HFX_PYRAMID_ATLAS", layout == PyramidLayout::Atlas ? "1" : "0"}});
        BoundsPass pass; // binds the surface it builds from to unit HFX_UNIT_SURFACE: first
        HeightBounds boundsA(a.textures().config(), layout), boundsB(b.textures().config(), layout);
        pass.refresh(a.textures(), boundsA, false);
        pass.refresh(b.textures(), boundsB, false);
        glBindTextureUnit(HFX_UNIT_SURFACE, a.textures().surface());
        boundsA.bind(0);
        glBindTextureUnit(HFX_UNIT_SURFACE1, b.textures().surface());
        boundsB.bind(1);
        glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SURFACE, block.id());
        const std::vector<glm::vec4> result = runHarness(p, segments);
        glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SURFACE, 0);
        float worstAbove = -1.0f, worstBelow = -1.0f, meanWidth = 0.0f;
        for (const glm::vec4& r : result) {
            worstAbove = std::max(worstAbove, r.x);
            worstBelow = std::max(worstBelow, r.y);
            meanWidth += (r.z - r.w) / float(kSegments);
        }
        EXPECT_LE(worstAbove, 0.0f) << edgeModeName(edges) << ": a height above the bounds' maximum";
        EXPECT_LE(worstBelow, 0.0f) << edgeModeName(edges) << ": a height below the bounds' minimum";
        // Bounds that hold by being the whole relief would say nothing: with the smooth layer,
        // narrower than the two layers' full range (the noise's own bounds cannot be).
        std::printf("[bounds] %s, %s: mean width %.3f\n", edgeModeName(edges),
                    layout == PyramidLayout::Atlas ? "atlas" : "mip chain", meanWidth);
        if (layers == 2) {
            EXPECT_LT(meanWidth, 0.95f);
        }
    }
}

TEST_F(TracerContract, TheTechniqueTableNamesItsShadersAndParsesItsNames) {
    for (const TechniqueInfo& t : kTechniqueTable) {
        EXPECT_EQ(parseTechnique(t.name), t.technique);
        EXPECT_EQ(&techniqueInfo(t.technique), &t);
        EXPECT_FALSE(surfaceShader(t.shader).text.empty()) << t.shader;
        EXPECT_NE(techniqueTableMarkdown().find(std::string("`") + t.name + "`"), std::string::npos);
    }
    EXPECT_NE(messageOf([] { parseTechnique("raytrace"); }).find(techniqueNames()), std::string::npos);
    EXPECT_NE(messageOf([] { surfaceShader("trace/none.glsl"); }).find("trace/none.glsl"), std::string::npos);
}

} // namespace
} // namespace hfx::test
