// A planet's rings (PlanetRings): their profile, and the two shadows between them and the planet
// against the exact geometry traced here on the CPU: the rings' shadow on the cloud tops where
// each pixel's sun ray crosses them, as deep as their opacity along it; the planet's shadow on
// the rings as the share of the sun's disc that the planet's disc covers.

#include "support/Fixtures.h"

#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/PlanetRings.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/tools/ImageFiles.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <optional>
#include <vector>

namespace hfx::test {
namespace {

class PlanetRingsTest : public DeviceTest {};

constexpr int kImage = 360;
constexpr double kPi = std::numbers::pi;

/// The profile's opacity averaged over [s0, s1] of its span (0 beyond it), texel by texel.
double meanOpacity(const std::vector<glm::vec4>& profile, double s0, double s1) {
    const int n = int(profile.size());
    auto at = [&](double s) { // linear between texel centres, 0 beyond the edges
        const double x = s * n - 0.5;
        const int i = int(std::floor(x));
        const double f = x - i;
        auto texel = [&](int k) { return k < 0 || k >= n ? 0.0 : double(profile[size_t(k)].a); };
        return texel(i) * (1.0 - f) + texel(i + 1) * f;
    };
    const int steps = std::max(1, int(std::ceil((s1 - s0) * n)));
    double sum = 0.0;
    for (int k = 0; k < steps; ++k) sum += at(s0 + (s1 - s0) * (k + 0.5) / steps);
    return sum / steps;
}

/// The area where two discs of radii a and b, d apart, overlap.
double discOverlap(double a, double b, double d) {
    if (d >= a + b) return 0.0;
    if (d <= std::abs(a - b)) return kPi * std::min(a, b) * std::min(a, b);
    const double ca = std::clamp((d * d + a * a - b * b) / (2 * d * a), -1.0, 1.0);
    const double cb = std::clamp((d * d + b * b - a * a) / (2 * d * b), -1.0, 1.0);
    return a * a * (std::acos(ca) - ca * std::sqrt(1 - ca * ca)) + b * b * (std::acos(cb) - cb * std::sqrt(1 - cb * cb));
}

/// The share of a sun of angular radius `sun` towards `l` that the unit sphere at the origin
/// leaves uncovered, seen from q.
double sunlit(const glm::dvec3& q, const glm::dvec3& l, double sun) {
    const glm::dvec3 d = -q;
    const double distance = glm::length(d);
    if (glm::dot(d, l) <= 0.0) return 1.0;
    const double planet = std::asin(1.0 / distance);
    const double apart = std::atan2(glm::length(glm::cross(d, l)), glm::dot(d, l));
    return 1.0 - discOverlap(sun, planet, apart) / (kPi * sun * sun);
}

/// The display value's linear light (the frames are gamma 2.2 encoded).
double linear(double display) { return std::pow(display, 2.2); }
double luminance(const Image& image, int x, int y) {
    return 0.2126 * linear(image.at(x, y, 0)) + 0.7152 * linear(image.at(x, y, 1)) +
           0.0722 * linear(image.at(x, y, 2));
}

Camera cameraAt(glm::vec3 position) {
    Camera camera;
    camera.position = position;
    camera.target = {0.0f, 0.0f, 0.0f};
    camera.aspect = 1.0f;
    return camera;
}

/// The first hit of a pixel's ray (image rows top first) with the unit sphere, if any.
std::optional<glm::dvec3> sphereHit(const Ray& ray) {
    const double b = glm::dot(ray.origin, ray.direction), c = glm::dot(ray.origin, ray.origin) - 1.0;
    const double disc = b * b - c;
    if (disc < 0.0) return std::nullopt;
    return ray.origin + ray.direction * (-b - std::sqrt(disc));
}

/// A banded planet (no advected detail) with the default rings, one step in: its profile and a
/// unit sphere to draw it on.
struct RingedPlanet {
    explicit RingedPlanet(ClContext& cl)
        : planet(cl, {.gas = {.width = 128, .height = 64, .initialBands = 9.0f},
                      .detail = {.amount = 0.0f},
                      .rings = PlanetRingsConfig{}}),
          config(planet.rings() ? planet.rings()->config() : PlanetRingsConfig{}), profile(ringProfile(config)) {
        planet.update(1.0 / 30.0);
    }
    GasPlanetEffect planet;
    PlanetRingsConfig config;
    std::vector<glm::vec4> profile;
    Mesh sphere{makeSphere({.radius = 1.0f, .segments = 128, .rings = 64})};
};

TEST(PlanetRingsProfile, IsSeededBoundedAndHasTheMainRingsAndTheirGaps) {
    const PlanetRingsConfig config;
    const std::vector<glm::vec4> a = ringProfile(config), b = ringProfile(config);
    ASSERT_EQ(int(a.size()), config.texels);
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4))) << "the same seed, another profile";
    PlanetRingsConfig other = config;
    other.seed = 2;
    const std::vector<glm::vec4> c = ringProfile(other);
    EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(glm::vec4))) << "the seed changes nothing";
    for (const glm::vec4& t : a)
        for (int k = 0; k < 4; ++k) ASSERT_TRUE(t[k] >= 0.0f && t[k] <= 1.0f) << t[k];
    // Shares of the span from 1.24 to 2.27 radii: C ring, B ring, Cassini division, A ring, Encke gap.
    const double cRing = meanOpacity(a, 0.02, 0.26), bRing = meanOpacity(a, 0.32, 0.67);
    const double cassini = meanOpacity(a, 0.70, 0.76), aRing = meanOpacity(a, 0.79, 0.92);
    const double encke = meanOpacity(a, 0.937, 0.943);
    std::printf("[profile] mean opacity: C %.3f, B %.3f, Cassini %.3f, A %.3f, Encke %.3f\n", cRing, bRing, cassini,
                aRing, encke);
    EXPECT_LT(cRing, 0.3);
    EXPECT_GT(bRing, 0.7);
    EXPECT_LT(cassini, 0.25);
    EXPECT_GT(aRing, 2.0 * cassini);
    EXPECT_LT(encke, 0.5 * aRing);
    // Ringlets: within the B ring the opacity varies from texel to texel region.
    double lo = 1.0, hi = 0.0;
    for (double s = 0.32; s < 0.67; s += 0.01) {
        const double m = meanOpacity(a, s, s + 0.01);
        lo = std::min(lo, m);
        hi = std::max(hi, m);
    }
    EXPECT_GT(hi - lo, 0.1) << "no structure within the B ring";

    EXPECT_THROW(ringProfile({.inner = 0.9f}), Error);
    EXPECT_THROW(ringProfile({.inner = 2.0f, .outer = 1.5f}), Error);
    EXPECT_THROW(ringProfile({.opacity = std::nanf("")}), Error);
    EXPECT_THROW(ringProfile({.texels = 4}), Error);
    EXPECT_THROW(makeAnnulus(2.0f, 1.0f), Error);
}

TEST_F(PlanetRingsTest, ABadPlanetLookIsRefusedByName) {
    PlanetRings rings;
    SurfaceMaterial m{.shading = Shading::Planet, .planet = rings.look()};
    EXPECT_NO_THROW(m.validate());
    m.planet.ringProfile = 987654; // no texture
    try {
        m.validate();
        ADD_FAILURE() << "a missing profile texture was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("ringProfile"), std::string::npos) << e.what();
    }
    m.planet = rings.look();
    m.planet.ringInner = 0.5f;
    EXPECT_THROW(m.validate(), Error);
    m.planet = rings.look();
    m.planet.sunAngularRadius = -1.0f;
    EXPECT_THROW(m.validate(), Error);

    // Composed over a copy of the frame, the rings refuse a multisampled one by name.
    GlRenderbuffer colour = GlRenderbuffer::create(), depth = GlRenderbuffer::create();
    glNamedRenderbufferStorageMultisample(colour.id(), 4, GL_RGBA8, 64, 64);
    glNamedRenderbufferStorageMultisample(depth.id(), 4, GL_DEPTH_COMPONENT24, 64, 64);
    GlFramebuffer multisampled = GlFramebuffer::create();
    glNamedFramebufferRenderbuffer(multisampled.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.id());
    glNamedFramebufferRenderbuffer(multisampled.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    ASSERT_EQ(glCheckNamedFramebufferStatus(multisampled.id(), GL_DRAW_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    glBindFramebuffer(GL_FRAMEBUFFER, multisampled.id());
    glViewport(0, 0, 64, 64);
    Camera camera;
    camera.position = {0.0f, 3.0f, 5.0f};
    const std::string message = messageOf([&] { rings.draw(glm::mat4(1.0f), camera, DirectionalLight{}); });
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_NE(message.find("multisampled"), std::string::npos) << message;
}

TEST_F(PlanetRingsTest, TheirShadowFallsOnTheCloudTopsWhereTheSunsRayCrossesThemAsDeepAsTheyAreOpaque) {
    // The planet seen from below its rings' plane, lit from 24 degrees above it: the rings'
    // shadow lies across the southern hemisphere. Three frames: without the rings' look (A),
    // with it (B), and with no sunlight (C, the ambient alone). The frame is ambient + T x sun,
    // so the transmittance measured at a pixel is (B - C) / (A - C) in linear light; the CPU
    // traces the pixel's ray to the unit sphere, the sun's ray from there to the rings' plane,
    // and takes the profile's opacity there, averaged over the sun's disc, along the slant.
    const RingedPlanet ringed(cl());
    const auto& planet = ringed.planet;
    const auto& rc = ringed.config;
    const auto& profile = ringed.profile;
    const auto& sphere = ringed.sphere;
    SurfaceRenderer renderer;
    const Camera camera = cameraAt({0.0f, -1.4f, 2.8f});
    DirectionalLight light;
    light.direction = glm::normalize(glm::vec3(0.85f, 0.45f, 0.3f));
    light.color = {1.0f, 0.97f, 0.92f};
    light.ambient = {0.03f, 0.03f, 0.04f};
    RenderTarget target(kImage, kImage);
    auto frame = [&](const SurfaceMaterial& material, const DirectionalLight& l) {
        target.bind();
        target.clear();
        renderer.draw(sphere, glm::mat4(1.0f), planet.textures(), material, camera, l);
        return target.readColor();
    };
    SurfaceMaterial bare = planet.material(), shadowOnly = planet.material();
    bare.planet = PlanetLook{};
    shadowOnly.planet.ringShine = false; // their shadow alone: their light has a test of its own
    DirectionalLight dark = light;
    dark.color = glm::vec3(0.0f);
    const Image a = frame(bare, light), b = frame(shadowOnly, light), c = frame(shadowOnly, dark);
    writeImage(outputPath("planet_ring_shadow.png"), b);

    const glm::dvec3 l = glm::normalize(glm::dvec3(light.direction));
    const double mu = std::abs(l.y), span = rc.outer - rc.inner;
    int missed = 0, missedOff = 0, shadowed = 0;
    double sums[2][2] = {}; // [B ring, C ring][measured, traced]
    int counts[2] = {};
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            const std::optional<glm::dvec3> p = sphereHit(camera.rayThroughPixel(x + 0.5, kImage - y - 0.5, kImage, kImage));
            if (!p || glm::dot(*p, l) < 0.05) continue; // the day side only
            const double t = -p->y / l.y;               // along the light to the plane y = 0
            const double width = 2.0 * t * rc.sunAngularRadius / mu / span; // the sun's disc there, in the span
            const double s = (glm::length(*p + t * l) - rc.inner) / span;
            const double sun = luminance(a, x, y) - luminance(c, x, y);
            if (t <= 0.0 || s < -width - 0.01 || s > 1.0 + width + 0.01) { // the sun's ray misses the rings
                ++missed;
                if (std::abs(luminance(b, x, y) - luminance(a, x, y)) > 0.01 + 0.02 * luminance(a, x, y)) ++missedOff;
                continue;
            }
            if (sun < 0.02 || a.at(x, y, 0) > 0.98) continue; // too dim to measure, or clipped
            const double measured = (luminance(b, x, y) - luminance(c, x, y)) / sun;
            const double traced = std::pow(1.0 - meanOpacity(profile, s - 0.5 * width, s + 0.5 * width), 1.0 / mu);
            if (measured < 0.5) ++shadowed;
            const int zone = s > 0.32 && s < 0.67 ? 0 : s > 0.02 && s < 0.26 ? 1 : -1;
            if (zone < 0) continue;
            sums[zone][0] += measured;
            sums[zone][1] += traced;
            ++counts[zone];
        }
    std::printf("[ring shadow] %d day pixels whose sun ray misses the rings, %d of them changed; %d shadowed below 0.5\n",
                missed, missedOff, shadowed);
    for (int zone = 0; zone < 2; ++zone)
        std::printf("[ring shadow] %s ring: %d pixels, transmittance %.3f measured, %.3f traced\n", zone == 0 ? "B" : "C",
                    counts[zone], sums[zone][0] / std::max(counts[zone], 1), sums[zone][1] / std::max(counts[zone], 1));
    EXPECT_GT(missed, 5000);
    EXPECT_LT(missedOff, missed / 200) << "light that misses the rings was dimmed";
    ASSERT_GT(counts[0], 500) << "the B ring's shadow is not in the frame";
    ASSERT_GT(counts[1], 500) << "the C ring's shadow is not in the frame";
    const double bMeasured = sums[0][0] / counts[0], bTraced = sums[0][1] / counts[0];
    const double cMeasured = sums[1][0] / counts[1], cTraced = sums[1][1] / counts[1];
    EXPECT_NEAR(bMeasured, bTraced, 0.03);
    EXPECT_NEAR(cMeasured, cTraced, 0.05);
    EXPECT_LT(bMeasured, 0.3) << "the dense ring's shadow is pale";
    EXPECT_GT(cMeasured, bMeasured + 0.3) << "the faint ring shadows as deeply as the dense one";
}

/// viewRings' light: towards +x, 15 degrees above the rings' plane.
glm::dvec3 ringLight() { return glm::normalize(glm::dvec3(1.0, std::tan(15.0 * kPi / 180.0), 0.0)); }

/// Where pixel (x, y)'s ray (image rows top first) meets the rings' plane y = 0: t along the ray
/// (not positive: it never does), the point, and its share s of the span from inner to outer.
struct PlanePixel {
    Ray ray;
    double t;
    glm::dvec3 q;
    double s;
};
PlanePixel onRingPlane(const Camera& camera, int x, int y, const PlanetRingsConfig& rc) {
    const Ray ray = camera.rayThroughPixel(x + 0.5, kImage - y - 0.5, kImage, kImage);
    const double t = -ray.origin.y / ray.direction.y;
    const glm::dvec3 q = ray.origin + t * ray.direction;
    return {ray, t, q, (glm::length(q) - rc.inner) / (rc.outer - rc.inner)};
}

/// The rings alone (no planet drawn: its shadow is what is measured), seen from `eye`, lit by
/// ringLight() with a sun of `sun` radians, or not lit at all.
Image viewRings(float sun, bool lit, glm::vec3 eye) {
    PlanetRings rings({.sunAngularRadius = sun});
    RenderTarget target(kImage, kImage);
    target.bind();
    target.clear();
    DirectionalLight light;
    light.direction = glm::vec3(ringLight());
    light.color = lit ? glm::vec3(1.0f) : glm::vec3(0.0f);
    light.ambient = {0.03f, 0.03f, 0.04f};
    rings.draw(glm::mat4(1.0f), cameraAt(eye), light);
    return target.readColor();
}

TEST_F(PlanetRingsTest, ThePlanetsShadowOnThemIsTheShareOfTheSunsDiscItCovers) {
    // The sun term (frame minus the unlit frame) of a sharp sun (0.002 rad) and of a wide one
    // (0.08 rad, a penumbra many pixels wide). Where the CPU's exact circle overlap says the sharp
    // sun is whole, the wide sun's term over the sharp one's is the share of the wide disc left
    // uncovered; in the umbra both terms are 0; in full light they agree.
    const glm::vec3 eye(-2.0f, 5.0f, 3.0f);
    const Image sharp = viewRings(0.002f, true, eye), wide = viewRings(0.08f, true, eye);
    const Image unlit = viewRings(0.08f, false, eye);
    writeImage(outputPath("rings_penumbra.png"), wide);
    const Camera camera = cameraAt(eye);
    const glm::dvec3 l = ringLight();
    const PlanetRingsConfig rc;
    int umbra = 0, umbraLit = 0, full = 0, fullOff = 0, penumbra = 0;
    double error = 0.0, worst = 0.0;
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            const PlanePixel p = onRingPlane(camera, x, y, rc);
            if (!(p.t > 0.0) || p.s < 0.02 || p.s > 0.98) continue; // off the rings, or at their edges
            const double fSharp = sunlit(p.q, l, 0.002), fWide = sunlit(p.q, l, 0.08);
            const double termSharp = luminance(sharp, x, y) - luminance(unlit, x, y);
            const double termWide = luminance(wide, x, y) - luminance(unlit, x, y);
            if (fWide == 0.0) {
                ++umbra;
                if (termWide > 0.003 || termSharp > 0.003) ++umbraLit;
            } else if (fWide == 1.0) {
                ++full;
                if (std::abs(termWide - termSharp) > 0.01 + 0.02 * termSharp) ++fullOff;
            } else if (fSharp == 1.0 && termSharp > 0.1) {
                ++penumbra;
                const double e = std::abs(termWide / termSharp - fWide);
                error += e;
                worst = std::max(worst, e);
            }
        }
    std::printf("[planet shadow] umbra %d pixels (%d lit), full light %d (%d off), outer penumbra %d: share of the "
                "sun off by %.3f on average, %.3f at worst\n",
                umbra, umbraLit, full, fullOff, penumbra, error / std::max(penumbra, 1), worst);
    EXPECT_GT(umbra, 1000);
    EXPECT_EQ(umbraLit, 0);
    EXPECT_GT(full, 10000);
    EXPECT_LT(fullOff, full / 200);
    ASSERT_GT(penumbra, 300);
    EXPECT_LT(error / penumbra, 0.03);
    EXPECT_LT(worst, 0.12);
}

TEST_F(PlanetRingsTest, DenseRingsAreBrightOnTheirLitFaceAndDarkFromBehind) {
    // Single scattering in a slab: seen from the sunlit side the dense B ring outshines the faint
    // C ring; seen from the other side the sunlight must cross the slab first, so the faint ring,
    // which lets it through, outshines the dense one. Sun terms, averaged across each ring.
    const PlanetRingsConfig rc;
    double ratio[2];
    for (int side = 0; side < 2; ++side) {
        const glm::vec3 eye(-1.0f, side == 0 ? 5.0f : -5.0f, 3.0f);
        const Image lit = viewRings(0.002f, true, eye), unlit = viewRings(0.002f, false, eye);
        const Camera camera = cameraAt(eye);
        double sum[2] = {};
        int count[2] = {};
        for (int y = 0; y < kImage; ++y)
            for (int x = 0; x < kImage; ++x) {
                const PlanePixel p = onRingPlane(camera, x, y, rc);
                if (!(p.t > 0.0) || sunlit(p.q, ringLight(), 0.002) < 1.0 || sphereHit(p.ray)) continue;
                const int zone = p.s > 0.32 && p.s < 0.67 ? 0 : p.s > 0.02 && p.s < 0.26 ? 1 : -1;
                if (zone < 0) continue;
                sum[zone] += luminance(lit, x, y) - luminance(unlit, x, y);
                ++count[zone];
            }
        ASSERT_GT(count[0], 1000);
        ASSERT_GT(count[1], 1000);
        ratio[side] = (sum[0] / count[0]) / (sum[1] / count[1]);
    }
    std::printf("[ring faces] B ring over C ring: %.2fx from the lit face, %.2fx from the unlit face\n", ratio[0], ratio[1]);
    EXPECT_GT(ratio[0], 1.5);
    EXPECT_LT(ratio[1], 0.7);
}

/// The rings' light on the unit sphere's point p (its normal), for the sun towards l (unit; the
/// rings in the plane y = 0), as a share of the sun's, per colour: the irradiance of the light
/// the rings scatter once towards p (the face the sun lights where p is on its side of the
/// plane, else through the slab), integrated over the rings above p's horizon, less the part
/// in the planet's shadow; 8 profile texels a radial step (the renderer's: 128), a degree around
/// (its: 5.6).
glm::dvec3 ringShineAt(const glm::dvec3& p, const glm::dvec3& l, const PlanetRingsConfig& rc,
                       const std::vector<glm::vec4>& profile) {
    constexpr int kPerStep = 8, kAround = 360;
    const int radial = int(profile.size()) / kPerStep;
    const double dr = (rc.outer - rc.inner) / radial, da = 2.0 * kPi / kAround;
    const double mu0 = std::max(std::abs(l.y), 1e-3);
    const bool litFace = p.y * l.y > 0.0;
    auto scattered = [&](double tau, double mu) {
        if (litFace) return 2.0 * mu0 / (mu0 + mu) * (1.0 - std::exp(-tau * (1.0 / mu + 1.0 / mu0)));
        if (std::abs(mu - mu0) < 1e-6) return 2.0 * tau / mu * std::exp(-tau / mu);
        return 2.0 * mu0 / (mu - mu0) * (std::exp(-tau / mu) - std::exp(-tau / mu0));
    };
    glm::dvec3 light(0.0);
    for (int i = 0; i < radial; ++i) {
        const double r = rc.inner + (i + 0.5) * dr;
        glm::dvec3 albedo(0.0);
        double opacity = 0.0;
        for (int k = 0; k < kPerStep; ++k) {
            const glm::vec4& t = profile[size_t(i * kPerStep + k)];
            albedo += glm::dvec3(t.r, t.g, t.b) / double(kPerStep);
            opacity += t.a / double(kPerStep);
        }
        const double tau = -std::log(std::max(1.0 - opacity, 1e-6));
        double sum = 0.0;
        for (int j = 0; j < kAround; ++j) {
            const glm::dvec3 q(r * std::cos((j + 0.5) * da), 0.0, r * std::sin((j + 0.5) * da));
            const glm::dvec3 d = q - p;
            const double distance = glm::length(d), cosPoint = glm::dot(p, d) / distance;
            const double along = glm::dot(q, l);
            if (cosPoint <= 0.0 || (along < 0.0 && r * r - along * along < 1.0)) continue;
            const double mu = std::abs(p.y) / distance;
            if (mu > 0.0) sum += scattered(tau, mu) * cosPoint * mu / (distance * distance);
        }
        light += albedo * (sum * r * dr * da / kPi);
    }
    return light;
}

TEST_F(PlanetRingsTest, TheirLightOnTheNightSideIsWhatTheyScatterTowardsIt) {
    // The night side, seen from below the rings' plane, lit from 25 degrees below it: the
    // southern hemisphere sees the rings' lit face, the northern one their unlit face. Three
    // frames without ambient light: with the rings' light (B), without it (A), and with an
    // ambient of 1 and no sun (U: the cloud tops' albedo times their occlusion times the night
    // sky's share, HFX_NIGHT_SKY, where the sun is far below the horizon). The rings' light at
    // a pixel is then (B - A) / (U / 0.05) in linear light, per colour; the CPU integrates it
    // over the rings at the point the pixel's ray meets the sphere.
    const RingedPlanet ringed(cl());
    const auto& planet = ringed.planet;
    const auto& rc = ringed.config;
    const auto& profile = ringed.profile;
    const auto& sphere = ringed.sphere;
    SurfaceRenderer renderer;
    const Camera camera = cameraAt({2.6f, -0.9f, 1.2f});
    const glm::dvec3 l = glm::normalize(glm::dvec3(-std::cos(25.0 * kPi / 180.0), -std::sin(25.0 * kPi / 180.0), 0.3));
    DirectionalLight sun;
    sun.direction = glm::vec3(l);
    sun.color = glm::vec3(1.0f);
    sun.ambient = glm::vec3(0.0f);
    DirectionalLight sky = sun;
    sky.color = glm::vec3(0.0f);
    sky.ambient = glm::vec3(1.0f);
    RenderTarget target(kImage, kImage);
    auto frame = [&](bool shine, const DirectionalLight& light) {
        SurfaceMaterial m = planet.material();
        m.planet.ringShine = shine;
        target.bind();
        target.clear();
        renderer.draw(sphere, glm::mat4(1.0f), planet.textures(), m, camera, light);
        return target.readColor();
    };
    const Image b = frame(true, sun), a = frame(false, sun), u = frame(false, sky);
    writeImage(outputPath("planet_ring_shine.png"), b);

    // Per hemisphere: the mean measured and traced light over the night pixels, per colour.
    double measured[2][3] = {}, traced[2][3] = {};
    int count[2] = {};
    double without = 0.0; // the night's own light, without the rings'
    for (int y = 0; y < kImage; y += 6)
        for (int x = 0; x < kImage; x += 6) {
            const std::optional<glm::dvec3> p = sphereHit(camera.rayThroughPixel(x + 0.5, kImage - y - 0.5, kImage, kImage));
            if (!p || glm::dot(*p, l) > -0.5 || std::abs(p->y) < 0.1) continue; // deep night, off the equator
            const int side = p->y < 0.0 ? 0 : 1;
            const glm::dvec3 t = ringShineAt(*p, l, rc, profile);
            double base[3];
            bool usable = true;
            for (int c = 0; c < 3; ++c) {
                base[c] = std::pow(u.at(x, y, c), 2.2) / 0.05;
                usable = usable && u.at(x, y, c) > 0.08 && b.at(x, y, c) < 0.98;
            }
            if (!usable) continue;
            without += std::pow(a.at(x, y, 1), 2.2) / base[1];
            for (int c = 0; c < 3; ++c) {
                measured[side][c] += (std::pow(b.at(x, y, c), 2.2) - std::pow(a.at(x, y, c), 2.2)) / base[c];
                traced[side][c] += t[c];
            }
            ++count[side];
        }
    for (int side = 0; side < 2; ++side)
        std::printf("[ring shine] %s (%s face): %d pixels, measured (%.4f, %.4f, %.4f), traced (%.4f, %.4f, %.4f)\n",
                    side == 0 ? "south" : "north", side == 0 ? "lit" : "unlit", count[side],
                    measured[side][0] / std::max(count[side], 1), measured[side][1] / std::max(count[side], 1),
                    measured[side][2] / std::max(count[side], 1), traced[side][0] / std::max(count[side], 1),
                    traced[side][1] / std::max(count[side], 1), traced[side][2] / std::max(count[side], 1));
    EXPECT_LT(without / std::max(count[0] + count[1], 1), 0.002) << "the deep night is lit without the rings' light";
    for (int side = 0; side < 2; ++side) {
        ASSERT_GT(count[side], 200) << (side == 0 ? "south" : "north") << ": too few night pixels in view";
        for (int c = 0; c < 3; ++c) {
            const double m = measured[side][c] / count[side], t = traced[side][c] / count[side];
            EXPECT_GT(t, 0.005) << "no light to measure";
            EXPECT_NEAR(m, t, 0.12 * t) << (side == 0 ? "south" : "north") << ", colour " << c;
        }
    }
}

TEST_F(PlanetRingsTest, TheirLightIsKeptPerSunAndRemadeForANewOne) {
    // The renderer keeps the rings' light per sun elevation: a planet drawn under one sun, then
    // another, then the first again draws the first frame to the bit, and the second sun's frame
    // is a fresh renderer's. Both suns' frames show the rings' light (without it they differ),
    // or the comparisons would hold with any table.
    const RingedPlanet ringed(cl());
    const Camera camera = cameraAt({2.6f, -0.9f, 1.2f});
    RenderTarget target(96, 96);
    auto frame = [&](SurfaceRenderer& renderer, float elevationDegrees, bool shine = true) {
        DirectionalLight sun;
        const float e = elevationDegrees * float(kPi) / 180.0f;
        sun.direction = glm::vec3(-std::cos(e), std::sin(e), 0.3f);
        sun.ambient = glm::vec3(0.0f);
        target.bind();
        target.clear();
        SurfaceMaterial material = ringed.planet.material();
        material.planet.ringShine = shine;
        renderer.draw(ringed.sphere, glm::mat4(1.0f), ringed.planet.textures(), material, camera, sun);
        return target.readColor().pixels;
    };
    SurfaceRenderer renderer, fresh;
    const std::vector<float> first = frame(renderer, -25.0f), second = frame(renderer, -10.0f);
    EXPECT_NE(frame(fresh, -25.0f, false), first) << "no rings' light in the first sun's frame";
    EXPECT_NE(frame(fresh, -10.0f, false), second) << "no rings' light in the second sun's frame";
    EXPECT_EQ(frame(renderer, -25.0f), first);
    EXPECT_EQ(frame(fresh, -10.0f), second);
}

} // namespace
} // namespace hfx::test
