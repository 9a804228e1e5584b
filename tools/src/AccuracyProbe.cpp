#include "hfx/tools/AccuracyProbe.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/Source.h"
#include "hfx/effects/SurfaceUniforms.h"
#include "hfx/tools/Timing.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace hfx {
namespace {

constexpr float kPlaneSize = 2.0f;
constexpr float kDistance = 8.0f;

SurfaceMaterial materialOf(const AccuracyConfig& config) {
    return {.depthScale = config.depthScale,
            .minSamples = config.minSamples,
            .maxSamples = config.maxSamples,
            .lodThreshold = 100.0f, // mip level 0: the figures speak of the search, not the filter
            .shadows = config.shadows,
            .shadowSharpness = config.shadowSharpness,
            .pixelBudget = config.pixelBudget};
}

struct Spread {
    double mean = 0, p95 = 0, max = 0, over = 0; ///< over: the share above the threshold
};

/// Mean, 95th percentile, maximum and the share above `threshold` of a non-empty sample.
Spread spreadOf(std::vector<double>& values, double threshold) {
    std::sort(values.begin(), values.end());
    Spread s;
    size_t over = 0;
    for (double v : values) {
        s.mean += v;
        over += v > threshold;
    }
    s.mean /= double(values.size());
    s.p95 = values[std::min(values.size() - 1, size_t(0.95 * double(values.size())))];
    s.max = values.back();
    s.over = double(over) / double(values.size());
    return s;
}

} // namespace

double lockstepFetches(const std::vector<glm::vec4>& trace, int width, int height, int blockWidth, int blockHeight,
                       int cap, double restart) {
    double sum = 0.0;
    size_t drawn = 0;
    std::vector<double> rests; // what the capped pixels leave to the pass, in screen order of their blocks
    for (int by = 0; by < height; by += blockHeight)
        for (int bx = 0; bx < width; bx += blockWidth) {
            double most = 0.0;
            size_t count = 0;
            for (int y = by; y < std::min(by + blockHeight, height); ++y)
                for (int x = bx; x < std::min(bx + blockWidth, width); ++x) {
                    const float f = trace[size_t(y) * width + x].w;
                    if (f == 0.0f) continue; // not drawn
                    const double fetches = std::floor(double(f));
                    most = std::max(most, std::min(fetches, double(cap)));
                    if (fetches > cap) rests.push_back(fetches - cap + restart);
                    ++count;
                }
            sum += most * double(count);
            drawn += count;
        }
    const size_t lanes = size_t(blockWidth) * size_t(blockHeight);
    for (size_t i = 0; i < rests.size(); i += lanes) {
        const size_t end = std::min(i + lanes, rests.size());
        sum += *std::max_element(rests.begin() + i, rests.begin() + end) * double(end - i);
    }
    return drawn ? sum / double(drawn) : 0.0;
}

Camera accuracyCamera(double angleDegrees, float distance, float aspect) {
    const float elevation = float((90.0 - angleDegrees) * std::numbers::pi / 180.0);
    Camera c = Camera::orbit({0, 0, 0}, distance, 0.3f, elevation);
    if (angleDegrees < 1.0) c.up = {0, 0, -1}; // looking straight down
    c.aspect = aspect;
    c.fovY = 0.35f;
    c.nearPlane = 0.05f;
    c.farPlane = 50.0f;
    return c;
}

bool planePixelRay(const Camera& camera, float planeSize, int x, int y, int width, int height, glm::dvec2& uv0,
                   glm::dvec3& toEye) {
    return planePointRay(camera, planeSize, x + 0.5, y + 0.5, width, height, uv0, toEye);
}

bool planePointRay(const Camera& camera, float planeSize, double px, double py, int width, int height, glm::dvec2& uv0,
                   glm::dvec3& toEye) {
    const Ray ray = camera.rayThroughPixel(px, py, width, height);
    if (ray.direction.y >= 0) return false;
    const double t = -ray.origin.y / ray.direction.y;
    const glm::dvec3 p = ray.origin + t * ray.direction;
    const double half = planeSize / 2.0;
    if (std::abs(p.x) > half || std::abs(p.z) > half) return false;
    uv0 = {p.x / planeSize + 0.5, 0.5 - p.z / planeSize};
    // Texture space of makePlane: u along +X, v along -Z, normal +Y, all scaled by planeSize.
    const glm::dvec3 e = -ray.direction;
    toEye = glm::dvec3(e.x, -e.z, e.y) / double(planeSize);
    return true;
}

AccuracyProbe::AccuracyProbe(ClContext& cl, std::vector<float> heights, int size, float normalDepth, SurfaceFormat format,
                             PyramidLayout layout)
    : size_(size), exact_(heights, size, size, EdgeMode::Wrap), field_(cl, size, size, EdgeMode::Wrap, heights),
      surface_(cl, SurfacePipelineConfig::of(field_, normalDepth,
                                             // mip level 0 only: the figures speak of the search, not the filter
                                             {.mipmaps = false, .format = format})),
      plane_(makePlane({.size = kPlaneSize})), timedPlane_(makePlane({.size = kPlaneSize, .texcoordScale = 2.0f})),
      layout_(resolvedLayout(layout)), devicePass_(deviceTracePass()) {
    surface_.run(field_.buffer());
}

HeightBounds& AccuracyProbe::bounds() {
    if (!bounds_) bounds_ = std::make_unique<HeightBounds>(textures().config(), layout_);
    return *bounds_;
}

std::optional<ShadowLight> AccuracyProbe::shadowLight(const AccuracyConfig& config) const {
    if (!config.shadows || !carriesBounds(textures().config())) return std::nullopt;
    DirectionalLight l;
    l.direction = config.light;
    return flatSurfaceLight(SurfaceFrame::ofPlane({.size = kPlaneSize}), l, materialOf(config));
}

GlTime AccuracyProbe::timeTexelShadows(const AccuracyConfig& config, int repeats) {
    const std::optional<ShadowLight> light = shadowLight(config);
    if (!light) return {};
    std::vector<GlTime> times;
    // The pass as the exact tracer runs it before a draw that reads them, for heights just
    // uploaded: their bounds' build from them first, then the walks (GPU time by timer queries).
    for (int i = -kWarmupFrames; i < repeats; ++i) { // warm-ups: the programs' builds
        surface_.run(field_.buffer());
        const GlTime t = timeGl(timer_, "texel shadows",
                                [&] { texelPass_.draw(textures(), bounds(), *light, config.texelStride, texels_); });
        if (i >= 0) times.push_back(t);
    }
    return median(times);
}

TracePass deviceTracePass() {
    return glWorkarounds(currentGlRenderer()).traceInDraw ? TracePass::InDraw : TracePass::Compute;
}

/// The draw options of config: its beam start, its texel shadows (forced either way: the probe
/// measures them where asked, not where they would pay), its pass (AccuracyConfig::tracePass: Auto
/// is deviceTracePass(), so that two measures compare the same walks).
DrawOptions AccuracyProbe::drawOptions(Technique technique, const AccuracyConfig& config, bool traceOutput) const {
    TracePass pass = config.tracePass;
    if (pass == TracePass::Auto) pass = config.deferShadowWalks ? TracePass::InDraw : devicePass_;
    return {.technique = technique,
            .traceOutput = traceOutput,
            .beamStart = config.beamStart,
            .texelShadows = config.texelShadows ? TexelShadowChoice::On : TexelShadowChoice::Off,
            .texelStride = config.texelStride,
            .deferShadowWalks = config.deferShadowWalks,
            .tracePass = pass,
            .boundsLayout = layout_};
}

AccuracyResult AccuracyProbe::measure(Technique technique, const AccuracyConfig& config) {
    const int n = config.image;
    if (!target_ || target_->width() != n) target_ = std::make_unique<RenderTarget>(n, n, true);
    const Camera camera = accuracyCamera(config.angleDegrees, config.cameraDistance > 0.0f ? config.cameraDistance : kDistance);
    const SurfaceMaterial material = materialOf(config);
    DirectionalLight light;
    light.direction = config.light;
    target_->bind();
    target_->clear();
    Camera drawn = camera;
    drawn.jitter = glm::vec2(2.0 * config.jitterPixels / double(n));
    renderer_.draw(plane_, glm::mat4(1.0f), textures(), material, drawn, light, drawOptions(technique, config, true));
    const std::vector<glm::vec4> trace = target_->readTrace();
    const std::vector<glm::vec2> entries = target_->readEntry();

    // The light in texture space, in (u, v, h) units: h spans depthScale texture units.
    const glm::dvec3 l = glm::normalize(glm::dvec3(config.light));
    const glm::dvec3 lightUVH(l.x / kPlaneSize, -l.z / kPlaneSize, l.y / kPlaneSize / config.depthScale);
    auto shadowed = [&](glm::dvec2 uv, double h) {
        if (lightUVH.z <= 0.0) return true;
        const glm::dvec3 origin(uv, h + 1e-7);
        const double tMax = (1.0 - origin.z) / lightUVH.z;
        return exact_.intersect(origin, lightUVH, tMax).has_value();
    };
    // The cone edge (trace/hier.glsl's hfx_shadow): from a texel away, the light ray lowered by
    // 1 / sharpness of its climb; where it meets the surface and the ray does not, a soft shadow's
    // penumbra darkens the point.
    const glm::dvec3 coneEdge(lightUVH.x, lightUVH.y, lightUVH.z * (1.0 - 1.0 / double(config.shadowSharpness)));
    const double texelStep = 1.0 / size_ / std::max(std::max(std::abs(lightUVH.x), std::abs(lightUVH.y)), 1e-12);
    auto inPenumbra = [&](glm::dvec2 uv, double h) {
        const double tMax = (1.0 - h) / lightUVH.z;
        if (texelStep >= tMax) return false;
        return exact_.intersect(glm::dvec3(uv, h) + coneEdge * texelStep, coneEdge, tMax - texelStep).has_value();
    };

    const glm::dmat4 viewProj(camera.viewProjection());
    auto toPixel = [&](glm::dvec3 uvh) {
        const glm::dvec4 world((uvh.x - 0.5) * kPlaneSize, -(1.0 - uvh.z) * config.depthScale * kPlaneSize,
                               (0.5 - uvh.y) * kPlaneSize, 1.0);
        const glm::dvec4 clip = viewProj * world;
        return (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * double(n);
    };

    AccuracyResult r;
    std::vector<double> errors, pixelErrors;
    double depthSum = 0.0, fetchSum = 0.0;
    size_t agree = 0, over4CentreRay = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::vec4 t = trace[size_t(y) * n + x];
            if (t.w == 0.0f) continue; // not drawn
            glm::dvec2 uv0;
            glm::dvec3 toEye;
            // Pixels whose centre is within half a pixel of the plane's edge may be drawn by GL
            // and missed by the CPU ray, or the other way round.
            if (!planePixelRay(camera, kPlaneSize, x, y, n, n, uv0, toEye)) continue;
            const auto hit = exact_.traceView(uv0, toEye, config.depthScale);
            if (!hit) continue;
            // The traced point against an exact hit: texels apart, and pixels apart on the screen
            // (the texcoord error moved to the exact hit's height and projected, i.e. how many
            // pixels the texture's content is displaced; the traced point itself lies on the
            // pixel's ray, so projecting it would hide a tracer's error).
            auto texelError = [&](const HeightFieldHit& h) { return glm::length(glm::dvec2(t.x, t.y) - h.uv) * size_; };
            auto pixelError = [&](const HeightFieldHit& h) {
                return glm::length(toPixel(glm::dvec3(t.x, t.y, h.height)) - toPixel(glm::dvec3(h.uv, h.height)));
            };
            over4CentreRay += texelError(*hit) > 4.0;
            // A rasteriser interpolates the fragment's inputs on its subpixel grid, so the ray a
            // fragment traces is not quite the centre's (NVIDIA's offsets alone put the mean
            // screen error at 0.0011 px on the blocks at 80 degrees): the reference is the ray
            // the fragment traced, from the texcoords it was given towards the eye.
            // Where the fragment entered within 1e-4 texel of the centre's ray (a rasteriser
            // sampling at the centre, llvmpipe's undisturbed draws), that ray stands for its own.
            const glm::dvec2 entry(entries[size_t(y) * n + x]);
            std::optional<HeightFieldHit> own = hit;
            if (glm::length(entry - uv0) * size_ > 1e-4) {
                const glm::dvec3 onPlane((entry.x - 0.5) * kPlaneSize, 0.0, (0.5 - entry.y) * kPlaneSize);
                const glm::dvec3 eye = glm::normalize(glm::dvec3(camera.position) - onPlane);
                own = exact_.traceView(entry, glm::dvec3(eye.x, -eye.z, eye.y) / double(kPlaneSize), config.depthScale);
            }
            HeightFieldHit best = own ? *own : *hit;
            double error = texelError(best), screenError = pixelError(best);
            if (error > 1.0 || screenError > 0.5) {
                // Where that one is far off, the centre's ray and those kSubpixelTolerance around
                // it are candidates too (a ray grazing a peak within the float rounding of its
                // direction).
                if (texelError(*hit) < error) {
                    best = *hit;
                    error = texelError(best);
                    screenError = pixelError(best);
                }
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        glm::dvec2 uvN;
                        glm::dvec3 toEyeN;
                        if ((dx == 0 && dy == 0) ||
                            !planePointRay(camera, kPlaneSize, x + 0.5 + dx * kSubpixelTolerance,
                                           y + 0.5 + dy * kSubpixelTolerance, n, n, uvN, toEyeN))
                            continue;
                        const auto near = exact_.traceView(uvN, toEyeN, config.depthScale);
                        if (near && texelError(*near) < error) {
                            best = *near;
                            error = texelError(best);
                            screenError = pixelError(best);
                        }
                    }
            }
            errors.push_back(error);
            pixelErrors.push_back(screenError);
            depthSum += std::abs(double(t.z) - best.t);
            const double fetches = std::floor(double(t.w));
            fetchSum += fetches;
            if (config.shadows) {
                // Compare where the exact state is stable around the point and the surface
                // faces the light (elsewhere shading is dark whatever the shadow says).
                const double h = best.height, e = 1e-3;
                const glm::dvec3 normal = glm::normalize(glm::dvec3(
                    -(exact_.heightAt(best.uv + glm::dvec2(e, 0)) - exact_.heightAt(best.uv - glm::dvec2(e, 0))) /
                        (2 * e) * config.depthScale,
                    -(exact_.heightAt(best.uv + glm::dvec2(0, e)) - exact_.heightAt(best.uv - glm::dvec2(0, e))) /
                        (2 * e) * config.depthScale,
                    1.0));
                const glm::dvec3 lightTS = glm::normalize(glm::dvec3(l.x, -l.z, l.y));
                if (glm::dot(normal, lightTS) < 0.2) continue;
                const bool state = shadowed(best.uv, h);
                const double band = config.penumbraTexels / size_;
                bool stable = true;
                for (const glm::dvec2 d : {glm::dvec2(band, 0), glm::dvec2(-band, 0), glm::dvec2(0, band), glm::dvec2(0, -band)}) {
                    const glm::dvec2 q = best.uv + d;
                    if (shadowed(q, exact_.heightAt(q)) != state) {
                        stable = false;
                        break;
                    }
                }
                if (!stable) continue;
                if (!state && inPenumbra(best.uv, h)) {
                    ++r.penumbraPixels;
                    continue;
                }
                const double lit = 2.0 * (double(t.w) - fetches);
                ++r.shadowPixels;
                agree += (lit < 0.5) == state;
            }
        }
    r.pixels = errors.size();
    if (!errors.empty()) {
        const Spread texels = spreadOf(errors, 4.0), pixels = spreadOf(pixelErrors, 1.0);
        r.mean = texels.mean;
        r.p95 = texels.p95;
        r.max = texels.max;
        r.over4 = texels.over;
        r.meanPixels = pixels.mean;
        r.p95Pixels = pixels.p95;
        r.overPixel = pixels.over;
        r.over4CentreRay = double(over4CentreRay) / double(errors.size());
        r.depthMean = depthSum / errors.size();
        r.fetches = fetchSum / errors.size();
    }
    r.shadowAgreement = r.shadowPixels ? double(agree) / r.shadowPixels : 1.0;
    r.fetchesLanes8 = lockstepFetches(trace, n, n, 4, 2);
    r.fetchesLanes32 = lockstepFetches(trace, n, n, 8, 4);
    return r;
}

namespace {
// Closer than measure()'s camera, so the plane covers the frame at every angle up to 80.
Camera timedCamera(const AccuracyConfig& config, int width, int height) {
    return accuracyCamera(config.angleDegrees, kDistance * 0.22f, float(width) / float(height));
}
} // namespace

FetchCounts AccuracyProbe::countFetches(Technique technique, const AccuracyConfig& config, int width, int height) {
    RenderTarget target(width, height, true);
    DirectionalLight light;
    light.direction = config.light;
    target.bind();
    target.clear();
    renderer_.draw(timedPlane_, glm::mat4(1.0f), textures(), materialOf(config), timedCamera(config, width, height),
                   light, drawOptions(technique, config, true));
    const std::vector<glm::vec4> trace = target.readTrace();
    // One pixel per block: each lane on its own, the plain mean.
    FetchCounts counts{.mean = lockstepFetches(trace, width, height, 1, 1),
                       .lanes8 = lockstepFetches(trace, width, height, 4, 2),
                       .lanes32 = lockstepFetches(trace, width, height, 8, 4)};
    counts.lanes32Capped = counts.lanes32;
    for (const int cap : kStragglerCaps) {
        const double capped = lockstepFetches(trace, width, height, 8, 4, cap, kStragglerRestart);
        if (capped < counts.lanes32Capped) {
            counts.lanes32Capped = capped;
            counts.cap = cap;
        }
    }
    return counts;
}

namespace {
/// timeCompute's harness: a ray per invocation from a buffer (a: uv, parallax; b.x: the cosine of
/// the view), traced as surface.frag traces a pixel of a flat plane at mip level 0, then its soft
/// shadow to u_lightDir (world; the plane's texture space is x, -z, y of it); out: the hit, the
/// shadow and the fetches.
const SourceFile kComputeMain{"trace_compute.comp", R"(
layout(std430, binding = 0) readonly buffer HfxComputeRays { vec4 rays[]; };
layout(std430, binding = 1) writeonly buffer HfxComputeHits { vec4 hits[]; };
uniform int u_count;
void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= uint(u_count)) return;
    const vec4 a = rays[2 * i], b = rays[2 * i + 1];
    HfxRay ray;
    ray.uv = a.xy;
    ray.parallax = a.zw;
    ray.cosTheta = b.x;
    ray.level = 0.0;
    ray.samples = clamp(int(mix(float(u_maxSamples), float(u_minSamples), b.x)), 1, HFX_MAX_SAMPLES);
    ray.tolerance = 0.0;
    ray.start = 0.0;
    const HfxHit hit = hfx_trace(ray);
    const vec3 light = normalize(vec3(u_lightDir.x, -u_lightDir.z, u_lightDir.y));
    const float h0 = 1.0 - hit.depth;
    float shadow = 0.0;
    if (light.z > 0.0 && h0 < 1.0) {
        HfxShadowRay s;
        s.uv = hit.uv;
        s.h0 = h0;
        s.span = light.xy / light.z * u_depthScale * (1.0 - h0);
        s.level = 0.0;
        s.samples = u_shadowSamples;
        s.sharpness = u_shadowSharpness;
        shadow = hfx_shadow(s);
    }
    hits[i] = vec4(hit.uv, shadow, g_fetches);
}
)",
                                 "tools"};
} // namespace

GlTime AccuracyProbe::timeCompute(Technique technique, const AccuracyConfig& config, int width, int height,
                                  double* fetches) {
    const SurfaceMaterial material = materialOf(config);
    const SurfaceTextures& t = textures();
    const auto key = std::make_tuple(config.angleDegrees, width, height, config.depthScale); // the light is a uniform
    if (key != computeKey_) {
        // timeDraw's rays: its camera through every pixel centre, where they meet the plane
        // (texcoords twice the plane's span, as timedPlane_ repeats the field twice).
        const Camera camera = timedCamera(config, width, height);
        std::vector<glm::vec4> rays;
        rays.reserve(size_t(width) * height * 2);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const Ray r = camera.rayThroughPixel(x + 0.5, y + 0.5, width, height);
                if (r.direction.y >= 0.0) continue;
                const glm::dvec3 p = r.origin - r.origin.y / r.direction.y * r.direction;
                if (std::abs(p.x) > kPlaneSize / 2.0 || std::abs(p.z) > kPlaneSize / 2.0) continue;
                const glm::dvec3 e(-r.direction.x, r.direction.z, -r.direction.y); // to the eye, texture space
                const glm::dvec2 uv = 2.0 * glm::dvec2(p.x / kPlaneSize + 0.5, 0.5 - p.z / kPlaneSize);
                rays.emplace_back(glm::vec2(uv), glm::vec2(glm::dvec2(e) / e.z * double(config.depthScale)));
                rays.emplace_back(float(e.z / glm::length(e)), 0.0f, 0.0f, 0.0f);
            }
        computeRays_ = int(rays.size() / 2);
        if (computeRays_ == 0) throw Error("timeCompute: no pixel's ray meets the plane");
        computeIn_ = GlBuffer::create();
        computeOut_ = GlBuffer::create();
        glNamedBufferStorage(computeIn_.id(), GLsizeiptr(rays.size() * sizeof(glm::vec4)), rays.data(), 0);
        glNamedBufferStorage(computeOut_.id(), GLsizeiptr(size_t(computeRays_) * sizeof(glm::vec4)), nullptr, 0);
        computeKey_ = key;
    }
    const bool atlas = layout_ == PyramidLayout::Atlas;
    const auto programKey = std::make_tuple(technique, atlas, material.boundedSearch);
    auto it = computePrograms_.find(programKey);
    if (it == computePrograms_.end()) {
        const std::vector<SourceFile> parts = {
            {"trace_compute_header.comp", "#version 450 core\nlayout(local_size_x = 64) in;\n", "tools"},
            surfaceShader("bindings.glsl"), surfaceShader("surface/uniforms.glsl"), surfaceShader("surface/heights.glsl"),
            surfaceShader("trace/common.glsl"), surfaceShader(techniqueInfo(technique).shader), kComputeMain};
        it = computePrograms_
                 .emplace(programKey,
                          ShaderProgram::compute(parts, {{"HFX_BOUNDED_SEARCH", material.boundedSearch ? "1" : "0"},
                                                         {"HFX_PYRAMID_ATLAS", atlas ? "1" : "0"}}))
                 .first;
    }
    SurfaceUniforms u{.depthScale = config.depthScale,
                      .lightDir = glm::normalize(config.light),
                      .shadowSharpness = config.shadowSharpness,
                      .minSamples = config.minSamples,
                      .maxSamples = config.maxSamples,
                      .shadowSamples = material.shadowSamples};
    u.setField({t.config().width, t.config().height}, t.config().edges);
    if (!computeBlock_.id()) { // made once, refreshed every dispatch
        computeBlock_ = GlBuffer::create();
        glNamedBufferStorage(computeBlock_.id(), sizeof u, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    glNamedBufferSubData(computeBlock_.id(), 0, sizeof u, &u);
    if (carriesBounds(t.config())) {
        boundsPass_.refresh(t, bounds(), true); // and the atlas layout's cells (image unit 4), from the texels
        bounds().bind(0);
    }
    glBindTextureUnit(HFX_UNIT_SURFACE, t.surface());
    glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SURFACE, computeBlock_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, computeIn_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, computeOut_.id());
    const ShaderProgram& p = it->second;
    p.use();
    p.set("u_count", computeRays_);
    const GlTime time = timeGl(timer_, "compute", [&] { glDispatchCompute(GLuint((computeRays_ + 63) / 64), 1, 1); });
    timer_.clearSamples();
    if (fetches) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<glm::vec4> hits(static_cast<size_t>(computeRays_));
        glGetNamedBufferSubData(computeOut_.id(), 0, GLsizeiptr(hits.size() * sizeof(glm::vec4)), hits.data());
        double sum = 0.0;
        for (const glm::vec4& h : hits) sum += h.w;
        *fetches = sum / double(hits.size());
    }
    glUseProgram(0);
    glBindBufferBase(GL_UNIFORM_BUFFER, HFX_BLOCK_SURFACE, 0);
    return time;
}

GlTime AccuracyProbe::timeDraw(Technique technique, const AccuracyConfig& config, int width, int height, int repeats,
                               int warmups) {
    if (!timedTarget_ || timedTarget_->width() != width || timedTarget_->height() != height)
        timedTarget_ = std::make_unique<RenderTarget>(width, height);
    RenderTarget& target = *timedTarget_;
    const Camera camera = timedCamera(config, width, height);
    const SurfaceMaterial material = materialOf(config);
    DirectionalLight light;
    light.direction = config.light;
    std::vector<GlTime> times;
    for (int i = -std::max(warmups, 1); i < repeats; ++i) { // the first draw builds the shader
        if (i == 0) timer_.clearSamples(); // the passes of the counted draws only
        target.bind();
        const GlTime t = timeGl(timer_, "draw total", [&] {
            target.clear();
            renderer_.draw(timedPlane_, glm::mat4(1.0f), textures(), material, camera, light,
                           drawOptions(technique, config, false));
        });
        if (i >= 0) times.push_back(t);
    }
    lastPasses_.clear();
    for (const auto& [name, ms] : timer_.samples())
        if (!ms.empty()) lastPasses_[name] = median(ms);
    timer_.clearSamples();
    lastFrame_ = target.readColor();
    return median(times);
}

int AccuracyProbe::deferredWalks() const { return renderer_.tracer().deferredWalks(); }

} // namespace hfx
