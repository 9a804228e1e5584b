// Triplanar mapping (SurfaceMaterial::triplanar): the texcoords from the mesh's own position,
// projected along its axes. Each face along an axis traces the relief its projection makes
// exactly (the CPU's intersection), a face between two axes blends the two projections' pixels by
// their weights, a caster writes the depth its projection traces, and bad input is refused by name.

#include "support/Fields.h"
#include "support/Fixtures.h"
#include "support/References.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

namespace hfx::test {
namespace {

class Triplanar : public GlTest {};

/// The documented projection of `axis` for a face whose unit normal is `n` (SurfaceRenderer.h,
/// TriplanarMapping): texcoords = scale * (eu . p, ev . p), u turned on the axis's negative side;
/// dP/du and dP/dv along the face.
struct Projection {
    glm::dvec3 eu, ev, tangent, bitangent; // (tangent, bitangent: per texcoord, at scale 1)
    glm::dvec2 texcoords(glm::dvec3 p, double scale) const { return scale * glm::dvec2(glm::dot(eu, p), glm::dot(ev, p)); }
};
Projection projection(int axis, glm::dvec3 n) {
    const double side = n[axis] < 0.0 ? -1.0 : 1.0;
    glm::dvec3 ea(0.0);
    ea[axis] = 1.0;
    const glm::dvec3 eu = axis == 0 ? glm::dvec3(0, side, 0) : glm::dvec3(side, 0, 0);
    const glm::dvec3 ev = axis == 0 ? glm::dvec3(0, 0, 1) : axis == 1 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
    return {eu, ev, eu - glm::dot(n, eu) / n[axis] * ea, ev - glm::dot(n, ev) / n[axis] * ea};
}

/// A square of side 2 about the origin facing `n` (unit), its sides along `a` and n x a, subdivided;
/// each vertex's texcoords and tangents from `frame` (what a mesh of its own would carry).
MeshData square(glm::dvec3 n, glm::dvec3 a, const std::function<Projection(glm::dvec3)>& frame, double scale) {
    const glm::dvec3 b = glm::cross(n, a);
    constexpr int cells = 4;
    MeshData mesh;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            const glm::dvec3 p = a * (2.0 * i / cells - 1.0) + b * (2.0 * j / cells - 1.0);
            const Projection f = frame(p);
            mesh.vertices.push_back({glm::vec3(p), glm::vec3(n), glm::vec3(f.tangent / scale), glm::vec3(f.bitangent / scale),
                                     glm::vec2(f.texcoords(p, scale))});
        }
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const uint32_t v = uint32_t(j * (cells + 1) + i);
            mesh.indices.insert(mesh.indices.end(), {v, v + 1, v + cells + 2, v, v + cells + 2, v + cells + 1});
        }
    return mesh;
}

/// The relief the tests draw (SineRelief), field² texels.
constexpr int kField = 64;

/// A camera `degrees` off the world normal `normal` of a face through `centre`, 3 units away.
Camera cameraOnto(glm::vec3 centre, glm::vec3 normal, double degrees, float aspect) {
    const glm::vec3 side = glm::normalize(glm::cross(normal, std::abs(normal.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
    const float r = float(degrees * std::numbers::pi / 180.0);
    Camera camera;
    camera.position = centre + 3.0f * (std::cos(r) * normal + std::sin(r) * side);
    camera.target = centre;
    camera.up = std::abs(glm::dot(normal, glm::vec3(0, 1, 0))) > 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    camera.fovY = 0.7f;
    camera.aspect = aspect;
    camera.nearPlane = 0.1f;
    camera.farPlane = 20.0f;
    return camera;
}

TEST_F(Triplanar, EachFaceAlongAnAxisTracesTheReliefItsProjectionMakes) {
    constexpr int W = 160, H = 120;
    constexpr float depthScale = 0.12f, scale = 1.5f;
    const SineRelief relief(kField, depthScale);
    const HeightFieldTracer exact(relief.heights, kField, kField, EdgeMode::Wrap);
    // A model that turns, scales and moves the mesh: the projections stay the mesh's own.
    const glm::mat4 model = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), {0.3f, -0.2f, 0.1f}), 0.5f,
                                                   glm::normalize(glm::vec3(1, 2, 3))),
                                       glm::vec3(1.25f));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f, .triplanar = {.scale = scale}};
    const DirectionalLight light{.direction = {0.3f, 0.8f, 0.5f}};
    RenderTarget target(W, H, true);
    SurfaceRenderer renderer;
    for (int axis = 0; axis < 3; ++axis)
        for (const double side : {1.0, -1.0}) {
            glm::dvec3 n(0.0);
            n[axis] = side;
            SCOPED_TRACE(str("the face towards ", side > 0 ? "+" : "-", "xyz"[axis]));
            const glm::dvec3 a = axis == 0 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
            // The mesh's own texcoords are another projection's, which the mapping must not read.
            const Mesh face(square(n, a, [&](glm::dvec3) { return projection((axis + 1) % 3, glm::dvec3(1, 1, 1) / std::sqrt(3.0)); }, 0.7));
            const glm::dvec3 worldNormal = glm::normalize(glm::transpose(glm::inverse(glm::dmat3(model))) * n);
            const glm::dvec3 origin(model * glm::vec4(0, 0, 0, 1));
            const Camera camera = cameraOnto(glm::vec3(origin), glm::vec3(worldNormal), 50.0, float(W) / float(H));
            target.bind();
            target.clear();
            renderer.draw(face, model, relief.textures, material, camera, light,
                          {.technique = Technique::Hierarchical, .traceOutput = true});
            const std::vector<glm::vec4> trace = target.readTrace();
            const std::vector<float> depth = target.readDepth();
            // The face's frame in the world: the projection's dP/du, dP/dv through the model.
            const Projection p = projection(axis, n);
            const glm::dvec3 T = glm::dmat3(model) * p.tangent / double(scale), B = glm::dmat3(model) * p.bitangent / double(scale);
            const glm::dmat3 worldFromTexture(T, B, worldNormal * std::sqrt(glm::length(T) * glm::length(B)));
            const glm::dmat3 textureFromWorld = glm::inverse(worldFromTexture);
            const glm::dmat4 objectFromWorld = glm::inverse(glm::dmat4(model));
            const glm::dmat4 viewProj(camera.viewProjection());
            size_t traced = 0, off = 0, depthOff = 0;
            double worst = 0.0, worstDepth = 0.0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const Ray ray = camera.rayThroughPixel(x + 0.5, y + 0.5, W, H);
                    const double t = glm::dot(origin - ray.origin, worldNormal) / glm::dot(ray.direction, worldNormal);
                    const glm::dvec3 entry = ray.origin + t * ray.direction;
                    const glm::dvec3 object(objectFromWorld * glm::dvec4(entry, 1.0));
                    // Inside the square, away from its rim (where the rasteriser's coverage decides).
                    if (!(t > 0.0) || std::max(std::abs(glm::dot(object, p.eu)), std::abs(glm::dot(object, p.ev))) > 0.95)
                        continue;
                    const glm::dvec2 uv0 = p.texcoords(object, scale);
                    const auto hit = exact.traceView(uv0, textureFromWorld * (glm::dvec3(camera.position) - entry), depthScale);
                    const size_t i = size_t(y) * W + x;
                    if (!hit || !(trace[i].z > 0.0f)) continue;
                    ++traced;
                    const double error = glm::length(glm::dvec2(trace[i]) - hit->uv) * kField; // texels
                    worst = std::max(worst, error);
                    off += error > kDrawHitTexels;
                    const glm::dvec3 point = entry + worldFromTexture * glm::dvec3(hit->uv - uv0, -(1.0 - hit->height) * depthScale);
                    const glm::dvec4 clip = viewProj * glm::dvec4(point, 1.0);
                    const double windowDepth = 0.5 * clip.z / clip.w + 0.5;
                    worstDepth = std::max(worstDepth, std::abs(windowDepth - depth[i]));
                    depthOff += std::abs(windowDepth - depth[i]) > 1e-5;
                }
            std::printf("[face %c%c] %zu traced pixels, %zu off the exact hit by more than 0.1 texels (%.2g at most), "
                        "depths within %.2g\n",
                        side > 0 ? '+' : '-', "xyz"[axis], traced, off, worst, worstDepth);
            ASSERT_GT(traced, size_t(W * H / 4));
            EXPECT_LE(off, traced / 1000);
            EXPECT_EQ(depthOff, 0u);
        }
}

// A face between x and y: halfway, where the two projections weigh 0.5 each, and nearer x with a
// gentler power, where they weigh what the documented weights give (z none in both). Its pixels
// are the two projections' pixels (each drawn with a mesh whose texcoords and tangents are that
// projection's) blended by those weights in linear light; its trace output is the x projection's
// (the heaviest, the first of equals).
TEST_F(Triplanar, AFaceBetweenTwoAxesBlendsTheirProjectionsByWeight) {
    constexpr int W = 160, H = 120;
    constexpr float depthScale = 0.1f, scale = 1.25f;
    const SineRelief relief(kField, depthScale);
    const glm::dvec3 a(0, 0, 1);
    const SurfaceMaterial planar{.depthScale = depthScale, .lodThreshold = 100.0f};
    const DirectionalLight light{.direction = {0.2f, 0.9f, 0.4f}};
    RenderTarget target(W, H, true);
    SurfaceRenderer renderer;
    struct Case {
        glm::dvec3 normal;
        float sharpness;
    };
    for (const Case& c : {Case{glm::normalize(glm::dvec3(1, 1, 0)), 4.0f}, Case{glm::dvec3(0.8, 0.6, 0), 2.0f}}) {
        const glm::dvec3 n = c.normal;
        // The weights as TriplanarMapping documents them: max(|n| - 0.3, 0)^sharpness, normalised.
        const double wx = std::pow(n.x - 0.3, double(c.sharpness)), wy = std::pow(n.y - 0.3, double(c.sharpness));
        const double weightX = wx / (wx + wy);
        SCOPED_TRACE(str("x weighs ", weightX));
        SurfaceMaterial triplanar = planar;
        triplanar.triplanar = {.scale = scale, .sharpness = c.sharpness};
        const Camera camera = cameraOnto({0, 0, 0}, glm::vec3(n), 35.0, float(W) / float(H));
        const auto render = [&](const Mesh& mesh, const SurfaceMaterial& material, std::vector<glm::vec4>* trace) {
            target.bind();
            target.clear({0, 0, 0, 1});
            renderer.draw(mesh, glm::mat4(1.0f), relief.textures, material, camera, light,
                          {.technique = Technique::Hierarchical, .traceOutput = true});
            if (trace) *trace = target.readTrace();
            return target.readColor();
        };
        std::vector<glm::vec4> traceX, traceBlend;
        const Image x = render(Mesh(square(n, a, [&](glm::dvec3) { return projection(0, n); }, scale)), planar, &traceX);
        const Image y = render(Mesh(square(n, a, [&](glm::dvec3) { return projection(1, n); }, scale)), planar, nullptr);
        const Image blend = render(Mesh(square(n, a, [&](glm::dvec3) { return projection(2, glm::dvec3(0, 0, 1)); }, 0.5)),
                                   triplanar, &traceBlend);
        const auto linear = [](float v) { return std::pow(double(v), 2.2); };
        size_t covered = 0, apart = 0, saturated = 0, off = 0, traceOff = 0;
        double worst = 0.0, worstTrace = 0.0;
        for (int row = 0; row < H; ++row)
            for (int col = 0; col < W; ++col) {
                const size_t i = size_t(H - 1 - row) * W + col; // (the trace is bottom row first)
                if (!(traceX[i].z > 0.0f)) continue;
                ++covered;
                double colourApart = 0.0, error = 0.0;
                for (int k = 0; k < 3; ++k) {
                    const double expected =
                        std::pow(weightX * linear(x.at(col, row, k)) + (1.0 - weightX) * linear(y.at(col, row, k)), 1.0 / 2.2);
                    saturated += std::max(x.at(col, row, k), y.at(col, row, k)) > 254.5f / 255.0f;
                    error = std::max(error, std::abs(double(blend.at(col, row, k)) - expected));
                    colourApart = std::max(colourApart, std::abs(double(x.at(col, row, k) - y.at(col, row, k))));
                }
                apart += colourApart > 0.1;
                worst = std::max(worst, error);
                off += error > 2.5 / 255.0;
                // (Two programs, each its compiler's rounding: an H200's differ at almost every pixel by more than 1e-5.)
                const double hitApart = glm::length(glm::dvec2(traceBlend[i]) - glm::dvec2(traceX[i])) * kField;
                worstTrace = std::max(worstTrace, hitApart);
                traceOff += hitApart > kDrawHitTexels || std::abs(traceBlend[i].z - traceX[i].z) > 1e-3f;
            }
        std::printf("[x weighing %.3f] %zu pixels, %zu where the projections differ by 0.1, %zu channels saturated; the "
                    "blend off theirs by more than 2.5/255 at %zu (%.3g at most), its trace off the x projection's at %zu (%.2g "
                    "texels at most)\n",
                    weightX, covered, apart, saturated, off, worst, traceOff, worstTrace);
        ASSERT_GT(covered, size_t(W * H / 3));
        // The 8-bit target clamps: where a projection's highlight saturated it, the blend of the
        // unclamped radiances would be brighter than the blend of the clamped ones. None here.
        ASSERT_EQ(saturated, 0u);
        ASSERT_GT(apart, covered / 4); // (or the blend could be either projection alone)
        EXPECT_LE(off, covered / 200);
        EXPECT_LE(traceOff, covered / 200);
    }
}

// A triplanar caster writes the depth its projection traces along the light's rays: on a face
// towards +y, that of makePlane's texcoords (the same projection, a whole repeat apart), whatever
// texcoords the face's mesh carries; walking in the draw and in the compute pass (a convex mesh:
// the face lies in one plane), where each projection walks in its own plane of slots.
TEST_F(Triplanar, ACasterWritesTheDepthItsProjectionTraces) {
    constexpr int size = 128;
    constexpr float depthScale = 0.12f;
    const SineRelief relief(kField, depthScale);
    const Mesh plane(makePlane({.size = 2.0f, .texcoordScale = 2.0f, .subdivisions = 4}));
    // The same square, whose own texcoords the mapping must not read.
    MeshData faceData = square({0, 1, 0}, {1, 0, 0}, [](glm::dvec3) { return projection(2, {0, 0, 1}); }, 0.7);
    faceData.convex = true;
    const Mesh face(faceData);
    const SurfaceMaterial planar{.depthScale = depthScale, .lodThreshold = 100.0f};
    SurfaceMaterial triplanar = planar;
    triplanar.triplanar = {.scale = 1.0f};
    const Camera lightView = Camera::fromMatrices(glm::lookAt(glm::vec3(1.5f, 2.5f, 1.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0)),
                                                  glm::ortho(-1.8f, 1.8f, -1.8f, 1.8f, 0.5f, 6.0f));
    RenderTarget target(size, size);
    SurfaceRenderer renderer;
    const auto depthOf = [&](const Mesh& mesh, const SurfaceMaterial& material, TracePass pass) {
        target.bind();
        target.clear();
        renderer.drawShadow(mesh, glm::mat4(1.0f), relief.textures, material, lightView,
                            {.technique = Technique::Hierarchical, .tracePass = pass});
        EXPECT_EQ(renderer.tracer().lastCaster().computeTrace, pass == TracePass::Compute);
        return target.readDepth();
    };
    // (The plane in the draw, as the triplanar caster's rays are its rasteriser's: on a GPU the
    // plane's compute pass finds its rays from the screen, to another rounding.)
    const std::vector<float> expected = depthOf(plane, planar, TracePass::InDraw);
    const std::vector<float> flat = [&] {
        target.bind();
        target.clear();
        renderer.drawFlatShadow(plane, glm::mat4(1.0f), lightView);
        return target.readDepth();
    }();
    for (const TracePass pass : {TracePass::InDraw, TracePass::Compute}) {
        const std::vector<float> actual = depthOf(face, triplanar, pass);
        size_t covered = 0, off = 0, below = 0;
        float worst = 0.0f;
        for (size_t i = 0; i < expected.size(); ++i) {
            if (!(expected[i] < 1.0f)) continue;
            ++covered;
            worst = std::max(worst, std::abs(actual[i] - expected[i]));
            off += std::abs(actual[i] - expected[i]) > 1e-5f;
            below += expected[i] > flat[i] + 1e-4f;
        }
        std::printf("[caster, %s] %zu texels, %zu below the polygon, %zu off the planar caster's depth by more than "
                    "1e-5 (%.2g at most)\n",
                    pass == TracePass::Compute ? "a compute pass" : "the draw", covered, below, off, double(worst));
        ASSERT_GT(covered, size_t(size * size / 4));
        ASSERT_GT(below, covered / 2); // (or a caster writing the polygon's depth would pass)
        EXPECT_LE(off, covered / 1000);
    }
}

// In the compute pass the rays draw stores a ray for each projection it weighs, and the shading
// draw, another program, reads one for each it weighs: at the dead zone's edge a GPU's compilers
// may round a weight to 0 in one and just above in the other. A slot the rays draw left is then
// normal mapped at that weight (next to nothing), and only the heaviest projection's slot says
// whether the pixel is drawn. Played here by a copy of the shaders whose rays draw has a dead zone
// of 0.32 (the shading draw's 0.3): every pixel the draw draws is drawn, in the same colour.
// (Discarding the pixel instead left 1721 of the sphere's 29101 pixels as holes.)
TEST_F(Triplanar, AProjectionTheRaysDrawDidNotWeighIsNormalMappedNotAHole) {
    constexpr int W = 320, H = 180;
    constexpr float depthScale = 0.04f;
    const SineRelief relief(kField, depthScale);
    const Mesh sphere(makeSphere({}));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f,
                                   .triplanar = {.scale = 1.5f, .sharpness = 2.0f}};
    const DirectionalLight light{.direction = {0.7f, 0.45f, 0.3f}};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.4f, 0.4f, 0.3f);
    camera.aspect = float(W) / float(H);
    RenderTarget target(W, H, true);
    const auto draw = [&](TracePass pass) {
        SurfaceRenderer renderer; // (its programs compiled from the shaders of the moment)
        target.bind();
        target.clear();
        renderer.draw(sphere, glm::mat4(1.0f), relief.textures, material, camera, light,
                      {.technique = Technique::Hierarchical, .traceOutput = true, .tracePass = pass});
        EXPECT_EQ(renderer.tracer().last().computeTrace, pass == TracePass::Compute);
        return std::pair(target.readTrace(), target.readColor());
    };
    const auto [walkedTrace, walkedColor] = draw(TracePass::InDraw);
    const PatchedShaders narrower("triplanar_rays_dead_zone", "const float HFX_TRIPLANAR_DEAD_ZONE = 0.3;",
                                  "const float HFX_TRIPLANAR_DEAD_ZONE = HFX_COMPUTE_TRACE == 1 ? 0.32 : 0.3;");
    const auto [computedTrace, computedColor] = draw(TracePass::Compute);
    size_t drawn = 0, holes = 0, off = 0;
    for (size_t i = 0; i < walkedTrace.size(); ++i) {
        if (walkedTrace[i] == glm::vec4(0.0f)) continue;
        ++drawn;
        holes += computedTrace[i] == glm::vec4(0.0f);
    }
    for (size_t i = 0; i < walkedColor.pixels.size(); ++i)
        off += std::abs(walkedColor.pixels[i] - computedColor.pixels[i]) > 2.0f / 255.0f;
    std::printf("[dead zone 0.32 in the rays draw] %zu pixels drawn, %zu holes, %zu colour channels off by more than "
                "2/255\n",
                drawn, holes, off);
    ASSERT_GT(drawn, size_t(W * H / 4));
    EXPECT_EQ(holes, 0u);
    EXPECT_LE(off, walkedColor.pixels.size() / 2000);
}

TEST_F(Triplanar, BadMappingsAreRefusedByNameAndDrawNothing) {
    constexpr float depthScale = 0.1f;
    const SineRelief relief(kField, depthScale);
    SurfaceTextures clamped({.width = 16, .height = 16, .mipmaps = false, .edges = EdgeMode::Clamp});
    const Mesh plane(makePlane({}));
    const Camera camera = cameraOnto({0, 0, 0}, {0, 1, 0}, 30.0, 1.0f);
    RenderTarget target(32, 32);
    SurfaceRenderer renderer;
    const auto material = [&](TriplanarMapping mapping, bool clip = false) {
        return SurfaceMaterial{.depthScale = depthScale, .clipToPatch = clip, .triplanar = mapping};
    };
    const SurfaceLayer layers[] = {{.textures = &relief.textures, .texcoordScale = 1.0f, .weight = 0.5f},
                                   {.textures = &relief.textures, .texcoordScale = 2.0f, .weight = 0.5f}};
    struct Case {
        std::function<void()> draw;
        const char* named;
    };
    const Case cases[] = {
        {[&] { renderer.draw(plane, glm::mat4(1.0f), relief.textures, material({.scale = -1.0f}), camera, {}); },
         "SurfaceMaterial.triplanar.scale must be >= 0"},
        {[&] { renderer.draw(plane, glm::mat4(1.0f), relief.textures, material({.scale = NAN}), camera, {}); },
         "SurfaceMaterial.triplanar.scale must be >= 0"},
        {[&] { renderer.draw(plane, glm::mat4(1.0f), relief.textures, material({.scale = 1.0f, .sharpness = 0.5f}), camera, {}); },
         "SurfaceMaterial.triplanar.sharpness must be in [1, 64], got 0.5"},
        {[&] { renderer.draw(plane, glm::mat4(1.0f), relief.textures, material({.scale = 1.0f}, true), camera, {}); },
         "SurfaceMaterial.clipToPatch cannot be set with triplanar.scale > 0"},
        {[&] { renderer.draw(plane, glm::mat4(1.0f), layers, material({.scale = 1.0f}), camera, {}); },
         "SurfaceMaterial.triplanar draws a surface of one layer, got 2"},
        {[&] { renderer.draw(plane, glm::mat4(1.0f), clamped, material({.scale = 1.0f}), camera, {}); },
         "SurfaceMaterial.triplanar needs a surface that wraps both ways"},
    };
    for (const Case& c : cases) {
        target.bind();
        target.clear({0.2f, 0.4f, 0.6f, 1.0f});
        const Image before = target.readColor();
        const std::string message = messageOf(c.draw);
        EXPECT_NE(message.find(c.named), std::string::npos) << message;
        EXPECT_EQ(target.readColor().pixels, before.pixels) << c.named;
    }
}

} // namespace
} // namespace hfx::test
