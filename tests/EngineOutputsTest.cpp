// What an engine reads of a draw besides its colour: the screen motion its temporal anti-aliasing
// or motion blur reads (SurfaceRenderer::setMotionOutput), the traced point's normal, albedo and
// shading channels its deferred lighting reads (setSurfaceOutputs), and its other targets, which a
// draw must leave alone.

#include "support/Fields.h"
#include "support/References.h"
#include "support/Fixtures.h"

#include "hfx/core/Gl.h"
#include "hfx/core/Mesh.h"
#include "hfx/effects/PlanetRings.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace hfx::test {
namespace {

class MotionOutput : public GlTest {};
class DeferredOutputs : public GlTest {};

/// An engine's framebuffer: colour (RGBA8) in draw buffer 0, another target it keeps (RGBA32F, a
/// G-buffer's normals, say) in 1, the motion (RG32F) in 2, a float depth.
struct EngineTarget {
    static constexpr glm::vec4 kKept{7.0f, -3.0f, 0.25f, 42.0f};
    EngineTarget(int w, int h)
        : width(w), height(h), fbo(GlFramebuffer::create()), colour(GlTexture::create()), kept(GlTexture::create()),
          motion(GlTexture::create()), depth(GlTexture::create()) {
        glTextureStorage2D(colour.id(), 1, GL_RGBA8, w, h);
        glTextureStorage2D(kept.id(), 1, GL_RGBA32F, w, h);
        glTextureStorage2D(motion.id(), 1, GL_RG32F, w, h);
        glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, w, h);
        glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
        glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT1, kept.id(), 0);
        glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT2, motion.id(), 0);
        glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
        const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        glNamedFramebufferDrawBuffers(fbo.id(), 3, buffers);
    }
    void bind() const {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, width, height);
        const float black[4] = {0, 0, 0, 1}, none[4] = {1e9f, 1e9f, 0, 0}, far = 1.0f;
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, black);
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, &kKept.x);
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 2, none);
        glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
    }
    template <typename T> std::vector<T> read(const GlTexture& t, GLenum format, GLenum type) const {
        std::vector<T> out(size_t(width) * height);
        glGetTextureImage(t.id(), 0, format, type, GLsizei(out.size() * sizeof(T)), out.data());
        return out; // bottom row first
    }
    size_t keptChanged() const {
        size_t changed = 0;
        for (const glm::vec4& v : read<glm::vec4>(kept, GL_RGBA, GL_FLOAT)) changed += v != kKept;
        return changed;
    }
    int width, height;
    GlFramebuffer fbo;
    GlTexture colour, kept, motion, depth;
};

/// A point's motion as the renderer defines it: its viewport uv now (without the jitter) less then.
glm::dvec2 motionOf(const glm::dvec4& now, const glm::dvec4& then, glm::dvec2 jitter) {
    return 0.5 * ((glm::dvec2(now) / now.w - jitter) - glm::dvec2(then) / then.w);
}

// Each pixel's motion is its traced point's, reprojected by the previous frame's camera and
// carried back by its mesh's previous model: the relief's hit, not its polygon's (which moves
// otherwise: the parallax the relief shows), the sky's direction, a moving sphere's points; with
// the camera's jitter left out; for every technique, hier walking in the draw, in a compute pass,
// and with its light walks deferred to a pass of points after the draw. The engine's other target
// keeps what it held through every draw.
TEST_F(MotionOutput, EachPixelMovesAsItsTracedPointDoes) {
    constexpr int field = 64, W = 160, H = 120;
    constexpr float depthScale = 0.15f;
    const auto heights = sumOfSines(field, {{0.3, 2, 1, 0.0}, {0.15, -1, 2, 0.7}});
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = depthScale});
    textures.uploadTexels(sobelReference(heights, field, depthScale).data());
    textures.setAlbedo(Image{1, 1, 3, {0.5f, 0.5f, 0.5f}});
    const Mesh plane(makePlane({.size = 2.0f})), sphere(makeSphere({.radius = 0.35f}));
    const glm::vec3 sphereNow(0.45f, 0.45f, -0.3f), sphereThen(0.40f, 0.42f, -0.3f);
    const glm::mat4 sphereModel = glm::translate(glm::mat4(1.0f), sphereNow),
                    spherePrevious = glm::translate(glm::mat4(1.0f), sphereThen);
    const DirectionalLight light{.direction = {0.6f, 0.5f, 0.4f}};
    Camera previous = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.8f, 0.50f, 0.70f);
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.7f, 0.53f, 0.68f);
    previous.aspect = camera.aspect = float(W) / float(H);
    camera.jitter = glm::vec2(0.37f, -0.21f) * 2.0f / glm::vec2(W, H);
    camera.previousViewProjection = previous.viewProjection();
    EngineTarget target(W, H);
    SurfaceRenderer renderer;
    renderer.setMotionOutput(2);
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjection()));
    const glm::dmat4 then = glm::dmat4(*camera.previousViewProjection);
    const glm::dvec2 jitter(camera.jitter);
    const std::pair<const char*, DrawOptions> drawn[] = {
        {"normal mapping", {.technique = Technique::NormalMapping}},
        {"pom", {.technique = Technique::ParallaxOcclusion}},
        {"hier in the draw", {.technique = Technique::Hierarchical, .tracePass = TracePass::InDraw}},
        {"hier in a compute pass", {.technique = Technique::Hierarchical, .tracePass = TracePass::Compute}},
        {"hier, light walks deferred", {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::On,
                                        .deferShadowWalks = true, .tracePass = TracePass::InDraw}}};
    for (const auto& [name, options] : drawn) {
        SCOPED_TRACE(name);
        target.bind();
        renderer.drawSky(camera, light, WaterLook{});
        renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = depthScale, .lodThreshold = 100.0f}, camera, light,
                      options);
        DrawOptions moving = options;
        moving.previousModel = spherePrevious;
        renderer.draw(sphere, sphereModel, textures, {.depthScale = 0.02f, .lodThreshold = 100.0f}, camera, light, moving);
        if (options.deferShadowWalks) {
            EXPECT_GT(renderer.tracer().deferredWalks(), 0);
        }
        const auto depth = target.read<float>(target.depth, GL_DEPTH_COMPONENT, GL_FLOAT);
        const auto motion = target.read<glm::vec2>(target.motion, GL_RG, GL_FLOAT);
        // The sphere's pixels: where it alone writes the same depth. (Its traced points can lie
        // away from it: at its rim a walk in the entry's tangent plane goes on past the sphere.)
        target.bind();
        renderer.draw(sphere, sphereModel, textures, {.depthScale = 0.02f, .lodThreshold = 100.0f}, camera, light, moving);
        const auto sphereDepth = target.read<float>(target.depth, GL_DEPTH_COMPONENT, GL_FLOAT);
        size_t sky = 0, relief = 0, moved = 0, parallax = 0, off = 0;
        double worst = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * W + x;
                const glm::dvec2 ndc((x + 0.5) / W * 2.0 - 1.0, (y + 0.5) / H * 2.0 - 1.0);
                glm::dvec2 expected;
                if (depth[i] >= 1.0f) { // the sky: the pixel's direction
                    const glm::dvec4 far = inverse * glm::dvec4(ndc, 1.0, 1.0);
                    const glm::dvec3 dir = glm::dvec3(far) / far.w - glm::dvec3(camera.position);
                    expected = motionOf(glm::dvec4(ndc, 0.0, 1.0), then * glm::dvec4(dir, 0.0), jitter);
                    ++sky;
                } else {
                    glm::dvec4 p = inverse * glm::dvec4(ndc, 2.0 * depth[i] - 1.0, 1.0);
                    p /= p.w;
                    const bool onSphere = sphereDepth[i] == depth[i];
                    const glm::dvec4 carried = onSphere ? p + glm::dvec4(glm::dvec3(sphereThen - sphereNow), 0.0) : p;
                    expected = motionOf(glm::dvec4(ndc, 0.0, 1.0), then * carried, jitter);
                    if (onSphere) ++moved;
                    else {
                        ++relief;
                        // The polygon's point on this pixel's ray (the plane y = 0): its motion.
                        const glm::dvec3 eye(camera.position), along = glm::dvec3(p) - eye;
                        const glm::dvec3 polygon = eye + along * (-eye.y / along.y);
                        const glm::dvec2 flat = motionOf(glm::dvec4(ndc, 0.0, 1.0), then * glm::dvec4(polygon, 1.0), jitter);
                        parallax += glm::length((flat - expected) * glm::dvec2(W, H)) > 0.25;
                    }
                }
                const double error = glm::length((glm::dvec2(motion[i]) - expected) * glm::dvec2(W, H)); // pixels
                worst = std::max(worst, error);
                off += error > 0.01;
            }
        std::printf("[motion] %s: %zu sky, %zu relief (%zu moved by its parallax), %zu sphere pixels; %zu off by more than "
                    "0.01 pixels, %.4f at most\n",
                    name, sky, relief, parallax, moved, off, worst);
        // Not vacuous: sky, relief and sphere show, and the relief's parallax moves its pixels
        // otherwise than the polygon's (except normal mapping's, which draws the polygon).
        ASSERT_GT(sky, size_t(W * H / 10));
        ASSERT_GT(relief, size_t(W * H / 5));
        ASSERT_GT(moved, size_t(W * H / 50));
        if (options.technique != Technique::NormalMapping) {
            EXPECT_GT(parallax, relief / 4);
        }
        EXPECT_EQ(off, 0u) << "pixels whose motion is off by more than 0.01 pixels (measured: 2e-4 at most)";
        EXPECT_EQ(target.keptChanged(), 0u) << "the engine's other target was written";
    }
}

// A camera cut (the previous frame looked the other way): a point at or behind the previous eye
// was on no screen, and its motion is 0, not a division by its depth there (an infinity or a NaN
// in the engine's history at w = 0, a point thrown across the screen behind it).
TEST_F(MotionOutput, APointThePreviousFrameDidNotSeeHasNoMotion) {
    constexpr int field = 32, W = 96, H = 72;
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = 0.1f});
    textures.uploadTexels(sobelReference(sumOfSines(field, {{0.3, 2, 1, 0.0}}), field, 0.1f).data());
    const Mesh plane(makePlane({.size = 2.0f}));
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.5f, 0.3f, 0.6f);
    camera.aspect = float(W) / float(H);
    Camera away = camera;
    away.target = 2.0f * camera.position - camera.target; // from the same place, the other way
    camera.previousViewProjection = away.viewProjection();
    EngineTarget target(W, H);
    SurfaceRenderer renderer;
    renderer.setMotionOutput(2);
    target.bind();
    renderer.drawSky(camera, DirectionalLight{}, WaterLook{});
    renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, DirectionalLight{},
                  {.technique = Technique::Hierarchical});
    const auto depth = target.read<float>(target.depth, GL_DEPTH_COMPONENT, GL_FLOAT);
    const auto motion = target.read<glm::vec2>(target.motion, GL_RG, GL_FLOAT);
    size_t relief = 0, moved = 0, notFinite = 0;
    for (size_t i = 0; i < motion.size(); ++i) {
        notFinite += !std::isfinite(motion[i].x) || !std::isfinite(motion[i].y);
        if (depth[i] >= 1.0f) continue;
        ++relief;
        moved += motion[i] != glm::vec2(0.0f);
    }
    ASSERT_GT(relief, size_t(W * H / 4));
    EXPECT_EQ(notFinite, 0u);
    EXPECT_EQ(moved, 0u) << "of " << relief << " relief pixels, all behind the previous eye";
}

// A flat mesh's draw and the rings write colour buffer 0 alone, and the rings compose over it
// whatever the framebuffer's read buffer names.
TEST_F(MotionOutput, FlatMeshesAndRingsLeaveTheOtherTargetsAlone) {
    constexpr int W = 96, H = 72;
    EngineTarget target(W, H);
    SurfaceRenderer renderer;
    renderer.setMotionOutput(2);
    PlanetRings rings;
    const Mesh planet(makeSphere({}));
    const Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 4.0f, 0.3f, 0.35f);
    const DirectionalLight light{.direction = {0.5f, 0.4f, 0.6f}};
    auto frame = [&](GLenum readBuffer) {
        target.bind();
        glNamedFramebufferReadBuffer(target.fbo.id(), readBuffer);
        renderer.drawFlat(planet, glm::mat4(1.0f), camera, {0.8f, 0.5f, 0.3f, 1.0f}, &light);
        rings.draw(glm::mat4(1.0f), camera, light);
        GLint read = GL_NONE; // (the framebuffer is bound for reading too)
        glGetIntegerv(GL_READ_BUFFER, &read);
        EXPECT_EQ(GLenum(read), readBuffer) << "the read buffer was not put back";
        return target.read<glm::u8vec4>(target.colour, GL_RGBA, GL_UNSIGNED_BYTE);
    };
    const auto usual = frame(GL_COLOR_ATTACHMENT0);
    EXPECT_EQ(target.keptChanged(), 0u);
    const auto motion = target.read<glm::vec2>(target.motion, GL_RG, GL_FLOAT);
    size_t written = 0;
    for (const glm::vec2& m : motion) written += m != glm::vec2(1e9f, 1e9f);
    EXPECT_EQ(written, 0u) << "a flat mesh or the rings wrote motion";
    // Over the planet and the rings' pixels: not vacuous.
    size_t lit = 0;
    for (const glm::u8vec4& c : usual) lit += c.r > 0 || c.g > 0 || c.b > 0;
    ASSERT_GT(lit, size_t(W * H / 10));
    const auto readingKept = frame(GL_COLOR_ATTACHMENT1);
    EXPECT_EQ(readingKept, usual) << "the rings composed over the read buffer's target";
    EXPECT_EQ(target.keptChanged(), 0u);
}

// The rings' motion pass (PlanetRings::setMotionOutput): where they cover at least half of what
// lies behind (the dense rings), a pixel moves as its ring point does, reprojected by the previous
// frame's camera and carried back by the planet's previous model; through a gap or a faint ring
// it keeps the sky's motion behind. The colour is the frame drawn without the pass.
TEST_F(MotionOutput, TheRingsMoveTheirPixelsWhereTheyCoverMostOfThem) {
    constexpr int W = 160, H = 120;
    const PlanetRingsConfig config{.texels = 256};
    PlanetRings rings(config);
    SurfaceRenderer renderer;
    renderer.setMotionOutput(2);
    const DirectionalLight light{.direction = {0.5f, 0.4f, 0.6f}};
    const glm::vec3 centreNow(0.1f, 0.0f, 0.0f), centreThen(0.07f, 0.02f, 0.0f);
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), centreNow), previousModel = glm::translate(glm::mat4(1.0f), centreThen);
    Camera previous = Camera::orbit({0.0f, 0.0f, 0.0f}, 4.3f, 0.40f, 0.55f);
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 4.2f, 0.43f, 0.52f);
    previous.aspect = camera.aspect = float(W) / float(H);
    camera.jitter = glm::vec2(-0.31f, 0.17f) * 2.0f / glm::vec2(W, H);
    camera.previousViewProjection = previous.viewProjection();
    EngineTarget target(W, H);
    const auto frame = [&](int motionOutput) {
        rings.setMotionOutput(motionOutput);
        target.bind();
        renderer.drawSky(camera, light, WaterLook{});
        rings.draw(model, camera, light, previousModel);
        return target.read<glm::u8vec4>(target.colour, GL_RGBA, GL_UNSIGNED_BYTE);
    };
    const auto plain = frame(0);
    const auto withMotion = frame(2);
    EXPECT_EQ(withMotion, plain) << "the motion pass changed the colour";
    EXPECT_EQ(target.keptChanged(), 0u);
    const auto motion = target.read<glm::vec2>(target.motion, GL_RG, GL_FLOAT);
    // Each radius's cover, seen at cosine mu, over the profile's texels that its pixel's footprint
    // reaches (the draw reads the profile filtered over it: `footprint` texels across, the next
    // mip level's texels twice that, and the bilinear neighbours; past either edge the border,
    // no ring).
    const std::vector<glm::vec4> profile = ringProfile(config);
    const auto coverRange = [&](double s, double footprint, double mu) {
        const int centre = int(std::floor(s * config.texels)), reach = int(std::ceil(2.0 * std::max(footprint, 1.0))) + 2;
        glm::dvec2 range(1.0, 0.0);
        for (int k = centre - reach; k <= centre + reach; ++k) {
            const double opacity = k >= 0 && k < config.texels ? double(profile[size_t(k)].a) : 0.0;
            const double tau = -std::log(std::max(1.0 - opacity, 1e-6));
            const double cover = 1.0 - std::exp(-tau / mu);
            range = {std::min(range.x, cover), std::max(range.y, cover)};
        }
        return range;
    };
    const glm::dmat4 then(*camera.previousViewProjection);
    const glm::dvec2 jitter(camera.jitter);
    const glm::dvec3 centre(centreNow);
    size_t ring = 0, through = 0, off = 0, still = 0;
    double worst = 0.0;
    // The ring coordinate of the plane's point on the ray through (px, py).
    const auto ringAt = [&](double px, double py) {
        const Ray ray = camera.rayThroughPixel(px, py, W, H);
        const glm::dvec3 q = ray.origin + (-ray.origin.y / ray.direction.y) * ray.direction;
        return (glm::length(q - centre) - config.inner) / (config.outer - config.inner);
    };
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const Ray ray = camera.rayThroughPixel(x + 0.5, y + 0.5, W, H);
            const glm::dvec2 ndc((x + 0.5) / W * 2.0 - 1.0, (y + 0.5) / H * 2.0 - 1.0);
            const double t = -ray.origin.y / ray.direction.y;
            const glm::dvec3 q = ray.origin + t * ray.direction;
            const double s = ringAt(x + 0.5, y + 0.5);
            const double footprint = config.texels * std::max({std::abs(ringAt(x + 1.5, y + 0.5) - s), std::abs(ringAt(x - 0.5, y + 0.5) - s),
                                                               std::abs(ringAt(x + 0.5, y + 1.5) - s), std::abs(ringAt(x + 0.5, y - 0.5) - s)});
            const glm::dvec2 cover = t > 0.0 && s >= 0.0 && s <= 1.0 ? coverRange(s, footprint, std::abs(ray.direction.y)) : glm::dvec2(0.0);
            const bool covered = cover.x > 0.55, clear = cover.y < 0.45;
            if (!covered && !clear) continue; // (near half: the filtered profile decides)
            glm::dvec2 expected;
            if (covered) {
                // The ring point, carried back with the planet.
                const glm::dvec4 carried(q + glm::dvec3(centreThen - centreNow), 1.0);
                expected = motionOf(glm::dvec4(ndc, 0.0, 1.0), then * carried, jitter);
                ++ring;
                // Not vacuous: the sky behind moves otherwise.
                still += glm::length((motionOf(glm::dvec4(ndc, 0.0, 1.0), then * glm::dvec4(ray.direction, 0.0), jitter) -
                                      expected) * glm::dvec2(W, H)) < 0.25;
            } else {
                expected = motionOf(glm::dvec4(ndc, 0.0, 1.0), then * glm::dvec4(ray.direction, 0.0), jitter);
                ++through;
            }
            const double error = glm::length((glm::dvec2(motion[size_t(y) * W + x]) - expected) * glm::dvec2(W, H));
            worst = std::max(worst, error);
            off += error > 0.01;
        }
    std::printf("[rings' motion] %zu pixels the rings cover, %zu through a gap or the sky; %zu off by more than 0.01 "
                "pixels (%.4f at most); %zu ring pixels would move as the sky does\n",
                ring, through, off, worst, still);
    ASSERT_GT(ring, size_t(W * H / 20));
    ASSERT_GT(through, size_t(W * H / 4));
    EXPECT_LT(still, ring / 10);
    EXPECT_EQ(off, 0u);
    EXPECT_NE(messageOf([&] { rings.setMotionOutput(8); }).find("PlanetRings::setMotionOutput: the draw buffer must be 1 to 7"),
              std::string::npos);
    glm::mat4 nan(1.0f);
    nan[3][0] = std::nanf("");
    EXPECT_NE(messageOf([&] { rings.draw(model, camera, light, nan); }).find("the previous model must be finite"),
              std::string::npos);
}

TEST_F(MotionOutput, ABadMotionSetupIsRefusedByName) {
    SurfaceRenderer renderer;
    for (const int bad : {-1, 8})
        EXPECT_NE(messageOf([&] { renderer.setMotionOutput(bad); }).find("the draw buffer must be 1 to 7"), std::string::npos);
    EXPECT_EQ(renderer.motionOutput(), 0);
    constexpr int field = 32;
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = 0.1f});
    textures.uploadTexels(sobelReference(sumOfSines(field, {{0.3, 2, 1, 0.0}}), field, 0.1f).data());
    const Mesh plane(makePlane({}));
    EngineTarget target(64, 48);
    target.bind();
    Camera camera = cameraAtAngle(40, 3.0f, 4.0f / 3.0f);
    renderer.setMotionOutput(1);
    EXPECT_NE(messageOf([&] {
                  renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, {}, {.traceOutput = true});
              }).find("the motion output's draw buffer 1 is one the trace output writes"),
              std::string::npos);
    glm::mat4 nan(1.0f);
    nan[3][1] = std::nanf("");
    EXPECT_NE(messageOf([&] {
                  renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, {}, {.previousModel = nan});
              }).find("DrawOptions.previousModel must be finite"),
              std::string::npos);
    camera.previousViewProjection = nan;
    EXPECT_NE(messageOf([&] { renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, {}); })
                  .find("Camera.previousViewProjection must be finite"),
              std::string::npos);
    // Refused before anything was drawn.
    const auto motion = target.read<glm::vec2>(target.motion, GL_RG, GL_FLOAT);
    for (const glm::vec2& m : motion) ASSERT_EQ(m, glm::vec2(1e9f, 1e9f));
    // A target that cannot hold a negative motion (RGBA8: it would clamp to 0) is refused by name,
    // by the surface draw and the sky's.
    camera.previousViewProjection.reset();
    GlTexture unorm = GlTexture::create();
    glTextureStorage2D(unorm.id(), 1, GL_RGBA8, 64, 48);
    glNamedFramebufferTexture(target.fbo.id(), GL_COLOR_ATTACHMENT1, unorm.id(), 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(target.fbo.id(), 2, buffers);
    for (const std::string& m :
         {messageOf([&] { renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, {}); }),
          messageOf([&] { renderer.drawSky(camera, {}, WaterLook{}); })})
        EXPECT_NE(m.find("the motion (SurfaceRenderer::setMotionOutput) goes to draw buffer 1 of the bound framebuffer, "
                         "whose target is unsigned normalized"),
                  std::string::npos)
            << m;
    std::vector<glm::u8vec4> written(64 * 48);
    glGetTextureImage(unorm.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(written.size() * 4), written.data());
    for (const glm::u8vec4& w : written) ASSERT_EQ(w, glm::u8vec4(0)) << "a refused draw wrote";
    // Into a float target the same draws go.
    glNamedFramebufferTexture(target.fbo.id(), GL_COLOR_ATTACHMENT1, target.kept.id(), 0);
    EXPECT_EQ(messageOf([&] { renderer.draw(plane, glm::mat4(1.0f), textures, {.depthScale = 0.1f}, camera, {}); }), "(no error)");
}

/// The field's texels bilinearly filtered at uv as GL does (texel centres at (i + 0.5) / size,
/// wrapped), `texel(x, y)` giving each.
template <typename T, typename Texel>
T bilinear(glm::dvec2 uv, int size, Texel&& texel) {
    const glm::dvec2 s = uv * double(size) - 0.5, f = s - glm::floor(s);
    const glm::ivec2 i(glm::floor(s));
    auto at = [&](int dx, int dy) { return texel(((i.x + dx) % size + size) % size, ((i.y + dy) % size + size) % size); };
    return T((1 - f.x) * (1 - f.y)) * at(0, 0) + T(f.x * (1 - f.y)) * at(1, 0) + T((1 - f.x) * f.y) * at(0, 1) +
           T(f.x * f.y) * at(1, 1);
}

// A deferred engine lights the relief itself from what the draw writes of the traced point
// (SurfaceOutputs): the relief's normal there (the stored normals filtered at the hit, turned
// into the world), its albedo, its shading channels (filtered at the hit, not at the polygon),
// the self-shadow the draw's light casts there, the one the draw's own shading used, and the
// light it emits (the channels' heat, as embers); HFX's forward colour in buffer 0 is their
// Lambert shading plus that light. For POM and for hier walking in the draw and in a compute
// pass.
TEST_F(DeferredOutputs, ADeferredEngineReadsTheTracedPointsNormalAlbedoChannelsAndShadow) {
    constexpr int field = 64, W = 160, H = 120;
    constexpr float depthScale = 0.15f;
    const auto heights = sumOfSines(field, {{0.3, 2, 1, 0.0}, {0.15, -1, 2, 0.7}});
    const std::vector<float> texels = sobelReference(heights, field, depthScale);
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = depthScale});
    textures.uploadTexels(texels.data());
    textures.setAlbedo(Image{1, 1, 3, {0.6f, 0.4f, 0.2f}});
    // Roughness along u, occlusion along v: what a channel reads tells where it was read. Heat in
    // the left half, rising along v (none in the right half).
    std::vector<unsigned char> channels(size_t(field) * field * 4);
    for (int y = 0; y < field; ++y)
        for (int x = 0; x < field; ++x) {
            unsigned char* c = &channels[(size_t(y) * field + x) * 4];
            c[0] = static_cast<unsigned char>(x * 4), c[1] = static_cast<unsigned char>(255 - y * 2), c[2] = 0;
            c[3] = static_cast<unsigned char>(x < field / 2 ? 60 + y * 2 : 0);
        }
    textures.uploadChannels(channels.data());
    const Mesh plane(makePlane({.size = 2.0f}));
    const SurfaceMaterial material{.depthScale = depthScale, .lodThreshold = 100.0f, .specularStrength = 0.0f};
    const DirectionalLight light{.direction = {0.7f, 0.35f, 0.3f}};
    Camera camera = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.6f, 0.4f, 0.8f);
    camera.aspect = float(W) / float(H);
    // Colour, the trace output (1, 2: the hit's uv, its depth fraction and light; the entry's uv),
    // then the normal, albedo, channels and emission (3, 4, 5, 6).
    GlFramebuffer fbo = GlFramebuffer::create();
    std::vector<GlTexture> attachments;
    const GLenum formats[] = {GL_RGBA8, GL_RGBA32F, GL_RG32F, GL_RGBA32F, GL_RGBA32F, GL_RGBA32F, GL_RGBA16F};
    std::vector<GLenum> buffers;
    for (GLenum i = 0; i < 7; ++i) {
        attachments.push_back(GlTexture::create());
        glTextureStorage2D(attachments.back().id(), 1, formats[i], W, H);
        glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0 + i, attachments.back().id(), 0);
        buffers.push_back(GL_COLOR_ATTACHMENT0 + i);
    }
    GlTexture depth = GlTexture::create();
    glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, W, H);
    glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    glNamedFramebufferDrawBuffers(fbo.id(), GLsizei(buffers.size()), buffers.data());
    ASSERT_EQ(glCheckNamedFramebufferStatus(fbo.id(), GL_DRAW_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    auto read = [&](int i) {
        std::vector<glm::vec4> out(size_t(W) * H);
        glGetTextureImage(attachments[size_t(i)].id(), 0, GL_RGBA, GL_FLOAT, GLsizei(out.size() * sizeof(glm::vec4)), out.data());
        return out;
    };
    SurfaceRenderer renderer;
    renderer.setSurfaceOutputs({.normal = 3, .albedo = 4, .material = 5, .emission = 6});
    const glm::dvec3 l = glm::normalize(glm::dvec3(light.direction));
    const std::pair<const char*, DrawOptions> drawn[] = {
        {"pom", {.technique = Technique::ParallaxOcclusion, .traceOutput = true}},
        {"hier in the draw", {.technique = Technique::Hierarchical, .traceOutput = true, .tracePass = TracePass::InDraw}},
        {"hier in a compute pass", {.technique = Technique::Hierarchical, .traceOutput = true, .tracePass = TracePass::Compute}}};
    for (const auto& [name, options] : drawn) {
        SCOPED_TRACE(name);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, W, H);
        const float zero[4] = {0, 0, 0, 0}, far = 1.0f;
        for (int i = 0; i < 7; ++i) glClearNamedFramebufferfv(fbo.id(), GL_COLOR, i, zero);
        glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
        renderer.draw(plane, glm::mat4(1.0f), textures, material, camera, light, options);
        const auto colour = read(0), trace = read(1), entry = read(2), normal = read(3), albedo = read(4), channel = read(5),
                   emission = read(6);
        size_t relief = 0, shadowed = 0, apartFromEntry = 0, normalOff = 0, channelOff = 0, shadowOff = 0, colourOff = 0,
               albedoOff = 0, glowing = 0, emissionOff = 0;
        double worstNormal = 0.0, worstChannel = 0.0, worstColour = 0.0, worstEmission = 0.0;
        for (size_t i = 0; i < colour.size(); ++i) {
            if (!(trace[i].z > 0.0f) && trace[i] == glm::vec4(0.0f)) continue; // the background
            ++relief;
            const glm::dvec2 uv(trace[i]), at(entry[i]);
            // The stored normal filtered at the hit; the plane's frame: T = +x, B = -z, N = +y.
            const glm::dvec3 n = glm::normalize(bilinear<glm::dvec3>(uv, field, [&](int x, int y) {
                const float* t = &texels[(size_t(y) * field + x) * 4];
                return glm::dvec3(t[0], t[1], t[2]);
            }));
            const glm::dvec3 world = glm::normalize(glm::dvec3(n.x, n.z, -n.y));
            const double angle = std::acos(std::clamp(glm::dot(world, glm::normalize(glm::dvec3(normal[i]))), -1.0, 1.0));
            worstNormal = std::max(worstNormal, angle);
            normalOff += angle > 5e-3;
            auto channelsAt = [&](glm::dvec2 p) {
                return bilinear<glm::dvec2>(p, field, [&](int x, int y) {
                    const unsigned char* c = &channels[(size_t(y) * field + x) * 4];
                    return glm::dvec2(c[0], c[1]) / 255.0;
                });
            };
            // The heat filtered at the hit, emitted as embers (GL's filter weights: 8 bits).
            const double heat = bilinear<double>(uv, field, [&](int x, int y) {
                return channels[(size_t(y) * field + x) * 4 + 3] / 255.0;
            });
            const glm::dvec3 glow = emberReference(heat);
            const double emissionApart = glm::length(glow - glm::dvec3(emission[i]));
            worstEmission = std::max(worstEmission, emissionApart);
            emissionOff += emissionApart > 0.012 + 0.002 * glow.r; // (half-floats, 8-bit weights)
            glowing += glow.r > 0.05;
            const glm::dvec2 expected = channelsAt(uv);
            const double off = glm::length(expected - glm::dvec2(channel[i]));
            worstChannel = std::max(worstChannel, off);
            channelOff += off > 1.5 / 255.0; // (GL's filter weights: 8 bits on llvmpipe)
            apartFromEntry += glm::length(channelsAt(at) - expected) > 0.02;
            albedoOff += glm::length(glm::dvec4(albedo[i]) - glm::dvec4(0.6, 0.4, 0.2, 1.0)) > 1e-5;
            // The self-shadow the draw shaded with (the trace output's light, in half its fraction).
            const double lit = 2.0 * (trace[i].w - std::floor(trace[i].w));
            shadowOff += std::abs(lit - channel[i].z) > 2.5e-3;
            shadowed += channel[i].z < 0.9f;
            // The forward colour: Lambert of these (no specular), encoded for the 8-bit target.
            const glm::dvec3 a(albedo[i]), lin = a * glm::dvec3(light.ambient) * double(channel[i].y) +
                                                 double(channel[i].z) * glm::dvec3(light.color) * a *
                                                     std::max(glm::dot(glm::normalize(glm::dvec3(normal[i])), l), 0.0) +
                                                 glm::dvec3(emission[i]);
            for (int c = 0; c < 3; ++c) {
                const double diff = std::abs(std::pow(std::clamp(lin[c], 0.0, 1.0), 1.0 / 2.2) - colour[i][c]);
                worstColour = std::max(worstColour, diff);
                colourOff += diff > 1.5 / 255.0;
            }
        }
        std::printf("[surface outputs] %s: %zu relief pixels, %zu shadowed, %zu glowing, %zu whose channels at the entry "
                    "differ; normals within %.2g rad, channels within %.2g, emission within %.2g, colour within %.2g\n",
                    name, relief, shadowed, glowing, apartFromEntry, worstNormal, worstChannel, worstEmission, worstColour);
        ASSERT_GT(relief, size_t(W * H / 3));
        EXPECT_GT(shadowed, relief / 20);
        EXPECT_GT(apartFromEntry, relief / 4) << "the channels read at the polygon would pass as well";
        EXPECT_EQ(normalOff, 0u);
        EXPECT_EQ(channelOff, 0u);
        EXPECT_EQ(albedoOff, 0u);
        EXPECT_EQ(shadowOff, 0u);
        EXPECT_EQ(colourOff, 0u);
        EXPECT_GT(glowing, relief / 5);
        EXPECT_LT(glowing, relief * 4 / 5) << "the right half of the field has no heat";
        EXPECT_EQ(emissionOff, 0u);
    }
    // Deferred light walks would rewrite the colour and leave the self-shadow written: they stay
    // in the draw where the material is written.
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    renderer.draw(plane, glm::mat4(1.0f), textures, material, camera, light,
                  {.technique = Technique::Hierarchical, .texelShadows = TexelShadowChoice::On, .deferShadowWalks = true,
                   .tracePass = TracePass::InDraw});
    EXPECT_NE(renderer.tracer().last().texelShadows, nullptr);
    EXPECT_FALSE(renderer.tracer().last().deferredShadows);
}

TEST_F(DeferredOutputs, ABadLayoutIsRefusedByName) {
    SurfaceRenderer renderer;
    EXPECT_NE(messageOf([&] { renderer.setSurfaceOutputs({.normal = 8}); }).find("the normal: the draw buffer must be 1 to 7"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { renderer.setSurfaceOutputs({.normal = 3, .material = 3}); })
                  .find("the normal and the material would both go to draw buffer 3"),
              std::string::npos);
    renderer.setMotionOutput(2);
    EXPECT_NE(messageOf([&] { renderer.setSurfaceOutputs({.albedo = 2}); }).find("the motion and the albedo would both go to draw buffer 2"),
              std::string::npos);
    EXPECT_EQ(renderer.surfaceOutputs(), hfx::SurfaceOutputs{}) << "a refused layout was kept";
    renderer.setSurfaceOutputs({.normal = 3});
    EXPECT_NE(messageOf([&] { renderer.setMotionOutput(3); }).find("the motion and the normal would both go to draw buffer 3"),
              std::string::npos);
    EXPECT_EQ(renderer.motionOutput(), 2);
    renderer.setMotionOutput(0);
    renderer.setSurfaceOutputs({.normal = 1});
    constexpr int field = 32;
    SurfaceTextures textures({.width = field, .height = field, .mipmaps = false, .normalDepth = 0.1f});
    textures.uploadTexels(sobelReference(sumOfSines(field, {{0.3, 2, 1, 0.0}}), field, 0.1f).data());
    EngineTarget target(64, 48);
    target.bind();
    EXPECT_NE(messageOf([&] {
                  renderer.draw(Mesh(makePlane({})), glm::mat4(1.0f), textures, {.depthScale = 0.1f}, cameraAtAngle(40, 3.0f, 1.0f),
                                {}, {.traceOutput = true});
              }).find("the normal output's draw buffer 1 is one the trace output writes"),
              std::string::npos);
    // The normal into a target that clamps its negative components (RGBA8): refused by name.
    renderer.setSurfaceOutputs({.normal = 3});
    GlTexture unorm = GlTexture::create();
    glTextureStorage2D(unorm.id(), 1, GL_RGBA8, 64, 48);
    glNamedFramebufferTexture(target.fbo.id(), GL_COLOR_ATTACHMENT3, unorm.id(), 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(target.fbo.id(), 4, buffers);
    EXPECT_NE(messageOf([&] {
                  renderer.draw(Mesh(makePlane({})), glm::mat4(1.0f), textures, {.depthScale = 0.1f}, cameraAtAngle(40, 3.0f, 1.0f), {});
              }).find("the normal (SurfaceRenderer::setSurfaceOutputs) goes to draw buffer 3 of the bound framebuffer, whose "
                      "target is unsigned normalized"),
              std::string::npos);
    // The emission into a normalized target, which would clamp the embers' light at 1: refused.
    renderer.setSurfaceOutputs({.emission = 3});
    EXPECT_NE(messageOf([&] {
                  renderer.draw(Mesh(makePlane({})), glm::mat4(1.0f), textures, {.depthScale = 0.1f}, cameraAtAngle(40, 3.0f, 1.0f), {});
              }).find("the emission (SurfaceRenderer::setSurfaceOutputs) goes to draw buffer 3 of the bound framebuffer, whose "
                      "target is normalized: its values over 1 would clamp"),
              std::string::npos);
    EXPECT_NE(messageOf([&] { renderer.setSurfaceOutputs({.material = 4, .emission = 4}); })
                  .find("the material and the emission would both go to draw buffer 4"),
              std::string::npos);
}

} // namespace
} // namespace hfx::test
