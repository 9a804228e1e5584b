#include "hfx/effects/PlanetRings.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Error.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/core/Random.h"

#include "GlStateGuard.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>

namespace hfx {

void PlanetRingsConfig::validate() const {
    if (!(radius > 0.0f) || !std::isfinite(radius))
        throw Error(str("PlanetRingsConfig.radius must be positive, got ", radius));
    if (!(inner > radius && outer > inner) || !std::isfinite(outer))
        throw Error(str("PlanetRingsConfig: the rings must lie beyond the planet, radius ", radius, " < inner ", inner,
                        " < outer ", outer));
    if (!(opacity >= 0.0f && opacity <= 10.0f))
        throw Error(str("PlanetRingsConfig.opacity must be in [0, 10], got ", opacity));
    for (int c = 0; c < 3; ++c)
        if (!(color[c] >= 0.0f && color[c] <= 1.0f))
            throw Error(str("PlanetRingsConfig.color must lie in [0, 1], got ", color[c], " in channel ", c));
    if (!(sunAngularRadius >= 0.0f && sunAngularRadius <= 0.1f))
        throw Error(str("PlanetRingsConfig.sunAngularRadius must be in [0, 0.1] radians, got ", sunAngularRadius));
    if (texels < 16 || texels > 16384)
        throw Error(str("PlanetRingsConfig.texels must be in [16, 16384], got ", texels));
}

namespace {

/// A smooth 1D value noise in [-1, 1]: `cells` random values across [0, 1], blended by a quintic.
class ValueNoise {
public:
    ValueNoise(SplitMix64& random, int cells) : values_(size_t(cells) + 1) {
        for (float& v : values_) v = float(random.uniform(-1.0, 1.0));
    }
    float operator()(double s) const {
        const double x = std::clamp(s, 0.0, 1.0) * double(values_.size() - 1);
        const size_t i = std::min(size_t(x), values_.size() - 2);
        const double f = x - double(i), w = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
        return float(values_[i] + (values_[i + 1] - values_[i]) * w);
    }

private:
    std::vector<float> values_;
};

/// Saturn's main rings as shares of the span from the C ring's inner edge (1.24 radii) to the A
/// ring's outer edge (2.27): the normal optical depth and the albedo's brightness in each.
struct Zone {
    double from, to, tau, brightness;
};
constexpr std::array<Zone, 6> kZones{{
    {0.00, 0.28, 0.12, 0.55}, // C ring: faint and grey
    {0.28, 0.69, 2.0, 1.0},   // B ring: dense and bright
    {0.69, 0.77, 0.1, 0.5},   // the Cassini division
    {0.77, 0.935, 0.6, 0.9},  // A ring
    {0.935, 0.945, 0.01, 0.5}, // the Encke gap
    {0.945, 1.0, 0.5, 0.9},   // A ring, outside it
}};

/// The zones' depth and brightness at s, their edges softened over `soft` of the span.
std::pair<double, double> zoneAt(double s, double soft) {
    double tau = 0.0, brightness = 0.0;
    for (const Zone& z : kZones) {
        const double in = std::clamp((s - z.from) / soft + 0.5, 0.0, 1.0) * std::clamp((z.to - s) / soft + 0.5, 0.0, 1.0);
        tau += in * z.tau;
        brightness += in * z.brightness;
    }
    return {tau, brightness};
}

} // namespace

std::vector<glm::vec4> ringProfile(const PlanetRingsConfig& config) {
    config.validate();
    SplitMix64 random(config.seed);
    // Ringlets at four scales, from a tenth of the span to a few texels; the B ring's depth
    // swells towards its outer part, as Saturn's does.
    std::vector<ValueNoise> ringlets;
    for (int cells : {12, 60, 300, 1500}) ringlets.emplace_back(random, std::min(cells, config.texels / 2));
    const ValueNoise tint(random, 40);
    std::vector<glm::vec4> profile(size_t(config.texels));
    for (int i = 0; i < config.texels; ++i) {
        const double s = (i + 0.5) / config.texels;
        auto [tau, brightness] = zoneAt(s, 0.004);
        double wobble = 0.0, amplitude = 0.45;
        for (const ValueNoise& n : ringlets) {
            wobble += amplitude * n(s);
            amplitude *= 0.8;
        }
        if (s > 0.28 && s < 0.69) tau *= 0.6 + 0.8 * (s - 0.28) / 0.41;
        tau *= std::exp(wobble) * config.opacity;
        const double shade = std::clamp(brightness * (1.0 + 0.12 * tint(s) + 0.1 * wobble), 0.0, 1.0);
        const glm::vec3 albedo = glm::clamp(config.color * float(shade), 0.0f, 1.0f);
        profile[size_t(i)] = {albedo, float(1.0 - std::exp(-tau))};
    }
    return profile;
}

MeshData makeAnnulus(float inner, float outer, int segments) {
    if (!(inner >= 0.0f && outer > inner) || !std::isfinite(outer) || segments < 3)
        throw Error(str("makeAnnulus: needs 0 <= inner < outer and 3 segments or more, got ", inner, ", ", outer, ", ",
                        segments));
    MeshData mesh;
    const double step = 2.0 * std::numbers::pi / segments;
    const double reach = outer / std::cos(0.5 * step); // the polygon's edges touch the circle
    for (int i = 0; i <= segments; ++i) {
        const double a = i * step, c = std::cos(a), s = std::sin(a);
        for (const double r : {double(inner), reach}) {
            Vertex v;
            v.position = glm::vec3(glm::dvec3(r * c, 0.0, -r * s));
            v.normal = {0.0f, 1.0f, 0.0f};
            v.tangent = glm::vec3(glm::dvec3(c, 0.0, -s));     // dP/dr
            v.bitangent = glm::vec3(glm::dvec3(-s, 0.0, -c));  // along the circle, T x B = +Y
            v.texcoord = {float(r), float(i) / float(segments)};
            mesh.vertices.push_back(v);
        }
    }
    for (uint32_t i = 0; i < uint32_t(segments); ++i) {
        const uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3; // inner, outer; the next pair
        mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
    return mesh;
}

PlanetRings::PlanetRings(const PlanetRingsConfig& config)
    : config_(config), profile_(GlTexture::create()), annulus_(makeAnnulus(config.inner, config.outer)),
      program_(surfaceStage("surface.vert"), surfaceStage("rings.frag")) {
    const std::vector<glm::vec4> profile = ringProfile(config_); // validates
    const int levels = int(std::bit_width(unsigned(config_.texels)));
    HFX_GL_CHECK(glTextureStorage2D(profile_.id(), levels, GL_RGBA16F, config_.texels, 1));
    HFX_GL_CHECK(glTextureSubImage2D(profile_.id(), 0, 0, 0, config_.texels, 1, GL_RGBA, GL_FLOAT, profile.data()));
    HFX_GL_CHECK(glGenerateTextureMipmap(profile_.id()));
    const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f}; // beyond either edge: no rings, at every level
    glTextureParameterfv(profile_.id(), GL_TEXTURE_BORDER_COLOR, none);
    glTextureParameteri(profile_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(profile_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(profile_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(profile_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

PlanetLook PlanetRings::look() const {
    return {.radius = config_.radius,
            .ringInner = config_.inner,
            .ringOuter = config_.outer,
            .sunAngularRadius = config_.sunAngularRadius,
            .ringProfile = profile_.id()};
}

void PlanetRings::setMotionOutput(int drawBuffer) {
    checkDrawBuffer("PlanetRings::setMotionOutput", drawBuffer);
    motionOutput_ = drawBuffer;
}

void PlanetRings::draw(const glm::mat4& model, const Camera& camera, const DirectionalLight& light,
                       const std::optional<glm::mat4>& previousModel) {
    camera.validate();
    light.validate();
    checkModel(model);
    if (previousModel && !isFinite(*previousModel))
        throw Error(str("PlanetRings::draw: the previous model must be finite, got the columns ", columnsText(*previousModel)));
    checkClipControl(camera.reversedZ);
    checkOutputTarget(motionOutput_, "the rings' motion (PlanetRings::setMotionOutput)", TargetHolds::Negatives);
    GlStateGuard guard; // (it puts back the depth mask the draw turns off, among the rest)
    GLint viewport[4], drawFramebuffer = 0, readFramebuffer = 0;
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer);
    if (viewport[2] <= 0 || viewport[3] <= 0) return; // nothing to draw into (a minimised window)
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
    if (samples != 0) // a copy from it is an error, and a release build would compose over stale texels
        throw Error("PlanetRings::draw: the bound framebuffer is multisampled; the rings are composed over a copy "
                    "of it, which GL takes only from a single-sampled one (resolve it first and draw the rings into "
                    "the resolved target)");
    // What the frame holds behind the rings, which they are composed over in linear light.
    // Copied as the frame holds it: display values, which the shader decodes; linear ones, or an
    // sRGB target's, which its fetch decodes (a copy reads an sRGB buffer's stored values).
    const bool linear = writesLinear(colorOutput_);
    const GLenum format = !linear ? GL_RGBA8 : boundColorTarget().encodesSrgb ? GL_SRGB8_ALPHA8 : GL_RGBA16F;
    if (viewport[2] > behindWidth_ || viewport[3] > behindHeight_ || !behind_ || format != behindFormat_) {
        behindWidth_ = std::max(viewport[2], behindWidth_);
        behindHeight_ = std::max(viewport[3], behindHeight_);
        behindFormat_ = format;
        behind_ = GlTexture::create();
        HFX_GL_CHECK(glTextureStorage2D(behind_.id(), 1, format, behindWidth_, behindHeight_));
    }
    // From colour buffer 0, whatever the framebuffer's read buffer is (an engine's may name its
    // normals or its motion): the copy reads the read buffer.
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(drawFramebuffer));
    GLint readBuffer = GL_NONE, drawBuffer = GL_NONE;
    glGetIntegerv(GL_READ_BUFFER, &readBuffer);
    glGetIntegerv(GL_DRAW_BUFFER0, &drawBuffer);
    if (readBuffer != drawBuffer) glReadBuffer(GLenum(drawBuffer));
    HFX_GL_CHECK(glCopyTextureSubImage2D(behind_.id(), 0, 0, 0, viewport[0], viewport[1], viewport[2], viewport[3]));
    if (readBuffer != drawBuffer) glReadBuffer(GLenum(readBuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readFramebuffer));

    SurfaceUniforms u{.lightDir = glm::normalize(light.direction),
                      .lightColor = light.color,
                      .ambient = light.ambient,
                      .linearOutput = linear ? 1 : 0};
    setEye(u, camera);
    setTransform(u, model, camera.viewProjection());
    if (motionOutput_) setMotion(u, camera, model, previousModel);
    updateBlock(surfaceBlock_, HFX_BLOCK_SURFACE, u);
    updateBlock(planetBlock_, HFX_BLOCK_PLANET, planetUniforms(look(), model));
    glBindTextureUnit(HFX_UNIT_RING_PROFILE, profile_.id());
    glBindTextureUnit(HFX_UNIT_RING_BEHIND, behind_.id());
    program_.set("u_viewportOrigin", glm::ivec2(viewport[0], viewport[1]));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(camera.reversedZ ? GL_GREATER : GL_LESS);
    glDepthMask(GL_FALSE); // the rings hide behind the planet, and hide nothing drawn later
    {
        const DrawBuffersWritten colourOnly(1u);
        program_.use();
        const GpuScope scope("rings");
        annulus_.draw();
    }
    if (motionOutput_) {
        // The motion where the rings cover most of the pixel, and nothing else: colour buffer 0
        // masked with the rest.
        if (motionProgramOutput_ != motionOutput_) {
            motionProgram_ = ShaderProgram(surfaceStage("surface.vert"), surfaceStage("rings.frag"),
                                           {{"HFX_MOTION_OUTPUT", std::to_string(motionOutput_)}});
            motionProgramOutput_ = motionOutput_;
        }
        const DrawBuffersWritten motionOnly(1u << motionOutput_);
        motionProgram_.use();
        const GpuScope scope("rings' motion");
        annulus_.draw();
    }
}

} // namespace hfx
