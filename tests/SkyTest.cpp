// The water sky's clouds (WaterLook::cloudCover; shaders/shade/sky.glsl, hfx::skyColor). The CPU
// model covers the share of the sky the look asks for, moves with its drift and filters what a
// pixel cannot show; the sky pass draws the CPU's sky, the water mirrors it and lies in the
// clouds' shadows where the CPU says, and bad looks are refused by name.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/core/Error.h"
#include "hfx/core/Gl.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/Sky.h"
#include "hfx/effects/SurfaceRenderer.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace hfx::test {
namespace {

class Sky : public GlTest {};

/// The eye of the model's tests: at the world's origin, under the layer's height.
constexpr glm::vec3 kEye{0.0f};

/// A direction whose point on the cloud layer (one cloud height over the eye at the origin) is `p`.
glm::vec3 towards(glm::vec2 p) { return glm::normalize(glm::vec3(p.x, 1.0f, p.y)); }

TEST(SkyModel, CloudsCoverTheShareOfTheSkyOverheadTheLookAsks) {
    // Overhead (y > 0.8) every octave shows (a tight spread): the share of directions under a
    // cloud's middle (density > 0.5) is the cover, at and between the quantile table's entries,
    // in its tails too (covers of 0.03, 0.97 and 0.99 were 0.0045, 0.997 and 1.0 while the table
    // held only every 5%: the distribution is steep there).
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    for (const float cover : {0.03f, 0.1f, 0.25f, 0.4f, 0.5f, 0.73f, 0.9f, 0.97f, 0.99f}) {
        WaterLook look;
        look.cloudCover = cover;
        look.cloudScale = 1.5f;
        int clouded = 0, n = 0;
        for (; n < 200000; ++n) {
            // Skies far apart on the layer (a view overhead holds a few clouds), y > 0.8 in each.
            look.cloudDrift = {500.0f * uniform(random), 500.0f * uniform(random)};
            const glm::vec2 p(0.75f * uniform(random), 0.75f * uniform(random));
            clouded += cloudSample(look, kEye, towards(p), 1e-4f).density > 0.5f;
        }
        std::printf("cover %.2f: %.4f of the sky overhead clouded\n", double(cover), double(clouded) / n);
        EXPECT_NEAR(double(clouded) / n, cover, 0.02) << "cover " << cover;
    }
    WaterLook look;
    look.cloudCover = 0.0f;
    EXPECT_EQ(cloudSample(look, kEye, towards({0.1f, 0.2f}), 1e-4f).density, 0.0f) << "no cover, no clouds";
    look.cloudCover = 1.0f;
    EXPECT_GT(cloudSample(look, kEye, towards({0.1f, 0.2f}), 1e-4f).density, 0.5f) << "full cover is overcast";
    EXPECT_EQ(cloudSample(look, kEye, glm::normalize(glm::vec3(0.3f, -0.2f, 0.5f)), 1e-4f).density, 0.0f)
        << "clouds below the horizon";
}

TEST(SkyModel, TheLayerMovesByItsDriftInCloudHeights) {
    // A layer at one cloud height: a drift d (in cloud heights) shows at direction towards(p) the
    // clouds the undrifted layer showed at towards(p + d).
    WaterLook still, moved;
    still.cloudCover = moved.cloudCover = 0.5f;
    moved.cloudDrift = {0.37f, -0.21f};
    double worst = 0.0, spread = 0.0;
    for (int i = 0; i < 400; ++i) {
        const glm::vec2 p(-0.6f + 0.003f * float(i), 0.2f + 0.001f * float(i));
        const float a = cloudSample(moved, kEye, towards(p), 1e-4f).density;
        const float b = cloudSample(still, kEye, towards(p + moved.cloudDrift), 1e-4f).density;
        worst = std::max(worst, double(std::abs(a - b)));
        spread = std::max(spread, double(std::abs(a - cloudSample(still, kEye, towards(p), 1e-4f).density)));
    }
    // (Only the fade towards the horizon differs, 1 - exp(-8 y) at the two directions' heights.)
    EXPECT_LT(worst, 0.03) << "the drift is not a shift of the layer in cloud heights";
    EXPECT_GT(spread, 0.5) << "the drift did not move the clouds";
}

TEST(SkyModel, CloudsNearTheHorizonShowWhatAPixelCoversRatherThanAliasing) {
    // 2 and 5 degrees over the horizon a pixel (2 mrad square) spans more of the layer than the
    // finer octaves' cells. What it should show is the mean of the clouds over it (16 x 16 sharp
    // samples across it): filtered over its width the clouds come nearer that than one sharp
    // sample at its middle (a spread of 0, what an unfiltered noise draws, aliased: the next
    // pixel another cell). Over 600 pixels along the horizon at each elevation.
    WaterLook look;
    look.cloudCover = 0.5f;
    const float pixel = 0.002f;
    auto dirAt = [](float azimuth, float e) {
        return glm::vec3(std::cos(e) * std::sin(azimuth), std::sin(e), -std::cos(e) * std::cos(azimuth));
    };
    for (const float elevation : {0.04f, 0.08f}) {
        double filtered = 0.0, sampled = 0.0, shown = 0.0;
        const int n = 600, sub = 16;
        for (int i = 0; i < n; ++i) {
            const float azimuth = 3.0f * pixel * float(i);
            double mean = 0.0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b)
                    mean += cloudSample(look, kEye, dirAt(azimuth + pixel * ((a + 0.5f) / sub - 0.5f), elevation + pixel * ((b + 0.5f) / sub - 0.5f)), 0.0f).density;
            mean /= sub * sub;
            filtered += std::abs(cloudSample(look, kEye, dirAt(azimuth, elevation), pixel).density - mean);
            sampled += std::abs(cloudSample(look, kEye, dirAt(azimuth, elevation), 0.0f).density - mean);
            shown += mean > 0.1;
        }
        std::printf("%.2f rad up: mean error against the pixel's mean cloud %.4f filtered, %.4f sampled; %.0f of %d "
                    "pixels clouded\n",
                    double(elevation), filtered / n, sampled / n, shown, n);
        EXPECT_LT(filtered / n, 0.8 * sampled / n) << "the finer octaves alias " << elevation << " rad up";
        EXPECT_GT(shown, 0.1 * n) << "too few clouds to test " << elevation << " rad up";
    }
}

/// Overhead (the layer's points within half a cloud height of the eye's zenith), the clouds' runs
/// along the sun's way across the layer: the mean luminance of the sky a tenth of a cell inside
/// each run's sunward edge, over that a tenth of a cell inside its far edge, and the runs.
std::pair<double, int> sunwardOverFarSide(WaterLook look, const DirectionalLight& light) {
    const glm::vec3 l = glm::normalize(light.direction);
    const glm::vec2 flat{l.x, l.z};
    const glm::vec2 way = glm::length(flat) > 1e-6f ? glm::normalize(flat) : glm::vec2(1.0f, 0.0f);
    const glm::vec2 across{-way.y, way.x};
    const float step = 0.004f, inset = 0.1f / look.cloudScale;
    auto luminance = [&](glm::vec2 p) {
        const glm::vec3 c = skyColor(look, light, kEye, towards(p), 1e-4f);
        return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    };
    auto clouded = [&](glm::vec2 p) { return cloudSample(look, kEye, towards(p), 1e-4f).density > 0.5f; };
    double sunward = 0.0, far = 0.0;
    int runs = 0;
    for (int sky = 0; sky < 80; ++sky) {
        look.cloudDrift = {37.1f * float(sky), -23.3f * float(sky)};
        for (int line = -10; line <= 10; ++line) {
            const glm::vec2 origin = across * (0.04f * float(line));
            // Towards the sun along the line: a run enters a cloud at its far edge and leaves it
            // at its sunward one (runs cut by the line's ends are left out).
            bool inside = clouded(origin - 0.5f * way);
            float entered = std::numeric_limits<float>::quiet_NaN();
            for (float s = -0.5f + step; s <= 0.5f; s += step) {
                const bool now = clouded(origin + s * way);
                if (now && !inside) entered = s;
                if (!now && inside && !std::isnan(entered) && s - entered > 3.0f * inset) {
                    far += luminance(origin + (entered + inset) * way);
                    sunward += luminance(origin + (s - inset) * way);
                    ++runs;
                }
                inside = now;
            }
        }
    }
    return {sunward / far, runs};
}

TEST(SkyModel, ACloudsSunlitSideIsBrighterThanItsFarSide) {
    // The sun's light reaches a cloud's underside through the cloud on its way: little of it on
    // the cloud's sunward side, all of it past its middle. Seen from below, a cloud under a low
    // sun is brighter on its sunward side than on its far side; under the sun overhead the
    // light comes down through the cloud's own depth, and neither side is brighter.
    WaterLook look;
    look.cloudCover = 0.4f;
    const DirectionalLight low{.direction = {-0.35f, 0.22f, -1.0f}, .color = {1.0f, 0.9f, 0.75f}}; // the demo's sun
    const DirectionalLight overhead{.direction = {0.0f, 1.0f, 0.0f}, .color = {1.0f, 0.9f, 0.75f}};
    const auto [lowRatio, lowRuns] = sunwardOverFarSide(look, low);
    const auto [overheadRatio, overheadRuns] = sunwardOverFarSide(look, overhead);
    std::printf("sunward side over far side: %.3f under the low sun (%d clouds), %.3f under the sun overhead (%d)\n",
                lowRatio, lowRuns, overheadRatio, overheadRuns);
    ASSERT_GT(lowRuns, 200) << "too few clouds to test";
    ASSERT_GT(overheadRuns, 200) << "too few clouds to test";
    EXPECT_GT(lowRatio, 1.06) << "a cloud's sunlit side is not brighter than its far side";
    EXPECT_NEAR(overheadRatio, 1.0, 0.03) << "under the sun overhead, one side of the clouds is brighter";
}

/// Pixel (x, y from the top) of `image`.
glm::vec3 pixelOf(const Image& image, int x, int y) {
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

/// The largest channel difference.
float apart(glm::vec3 a, glm::vec3 b) {
    const glm::vec3 d = glm::abs(a - b);
    return std::max({d.x, d.y, d.z});
}

TEST(SkyModel, TheHorizonIsTheCloudLayersMeanSeenEdgeOn) {
    // Far off the layer is seen edge on, more of it in a pixel than its octaves show: at the
    // horizon, and below it (what distant water fades into), the sky is the layer's mean. Under a
    // flat clear sky (the zenith's colour the horizon's, no glow about the sun), the demo's low
    // sun: the horizon is the mean of the sky overhead over many skies, within 0.03 at covers
    // 0.2, 0.6, 0.95 and 1 (overcast, the clouds' grey: the clear sky's colour, which the layer
    // used to fade into, was 0.16 to 0.32 off it); the sky 0.5 degrees up (a 2 mrad pixel) meets it
    // without a seam, and below the horizon it goes on.
    const DirectionalLight low{.direction = {-0.35f, 0.22f, -1.0f}, .color = {1.0f, 0.9f, 0.75f}};
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    for (const float cover : {0.2f, 0.6f, 0.95f, 1.0f}) {
        WaterLook look;
        look.cloudCover = cover;
        look.sunGlow = 0.0f;
        look.skyZenith = look.skyHorizon;
        glm::dvec3 overhead(0.0);
        const int n = 40000;
        for (int i = 0; i < n; ++i) {
            look.cloudDrift = {500.0f * uniform(random), 500.0f * uniform(random)};
            const glm::vec2 p(0.75f * uniform(random), 0.75f * uniform(random));
            overhead += glm::dvec3(skyColor(look, low, kEye, towards(p), 1e-4f));
        }
        overhead /= double(n);
        look.cloudDrift = {0.3f, -1.7f};
        glm::dvec3 above(0.0), horizon(0.0);
        float below = 0.0f;
        const int m = 600;
        for (int i = 0; i < m; ++i) {
            const float azimuth = 0.01f * float(i), up = 0.0087f;
            const glm::vec3 level(std::sin(azimuth), 0.0f, -std::cos(azimuth));
            const glm::vec3 h = skyColor(look, low, kEye, level, 0.002f);
            horizon += glm::dvec3(h);
            above += glm::dvec3(skyColor(look, low, kEye, glm::normalize(level + glm::vec3(0.0f, up, 0.0f)), 0.002f));
            below = std::max(below, apart(skyColor(look, low, kEye, glm::normalize(level - glm::vec3(0.0f, 0.3f, 0.0f)), 0.002f), h));
        }
        horizon /= double(m);
        above /= double(m);
        std::printf("cover %.2f: the sky overhead %.3f %.3f %.3f on average, the horizon %.3f %.3f %.3f, half a degree "
                    "up %.3f %.3f %.3f\n",
                    double(cover), overhead.x, overhead.y, overhead.z, horizon.x, horizon.y, horizon.z, above.x,
                    above.y, above.z);
        EXPECT_LT(apart(glm::vec3(horizon), glm::vec3(overhead)), 0.03f) << "cover " << cover;
        EXPECT_LT(apart(glm::vec3(above), glm::vec3(horizon)), 0.03f) << "a seam at the horizon, cover " << cover;
        EXPECT_LT(below, 1e-6f) << "below the horizon, cover " << cover;
        if (cover > 0.9f) {
            EXPECT_GT(apart(glm::vec3(horizon), look.skyHorizon), 0.15f) << "an overcast horizon is the clear sky's";
        }
    }
}

TEST(SkyModel, AnOvercastDecksGapsAreGreyAndShadedNotBlueAndSunlit) {
    // A deck that covers most of the sky lies under a higher veil: in its gaps (the layer's
    // density under 0.1) the sky is not the clear sky's blue, and the sun's light through them is
    // dimmed at least as at a cloud's edge. Under fair-weather cumulus (a cover of 0.6) the gaps
    // are the clear sky, and full sun reaches the sea through them. The look's own colours, the
    // demo's low sun, skies overhead far apart on the layer: how far the gaps' blue (blue less
    // red) lies from the clouds' (density over 0.9) towards the clear sky's in the same
    // directions (1: the clear sky's), and the most sunlight at points of the sea.
    const DirectionalLight low{.direction = {-0.35f, 0.22f, -1.0f}, .color = {1.0f, 0.9f, 0.75f}};
    std::mt19937 random(11);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    for (const float cover : {0.6f, 0.9f, 0.95f}) {
        WaterLook look, clear;
        look.cloudCover = cover;
        clear.cloudCover = 0.0f;
        double blue = 0.0, clearBlue = 0.0, cloudBlue = 0.0;
        float sunniest = 0.0f;
        int gaps = 0, clouds = 0;
        for (int i = 0; i < 40000; ++i) {
            look.cloudDrift = {500.0f * uniform(random), 500.0f * uniform(random)};
            const glm::vec3 dir = towards({0.75f * uniform(random), 0.75f * uniform(random)});
            const glm::vec3 sea(300.0f * uniform(random), 0.0f, 0.0f);
            sunniest = std::max(sunniest, cloudSunlight(look, low, sea, 1.0f));
            const float density = cloudSample(look, kEye, dir, 1e-4f).density;
            const glm::vec3 c = skyColor(look, low, kEye, dir, 1e-4f);
            if (density > 0.9f) {
                cloudBlue += c.b - c.r;
                ++clouds;
            }
            if (density >= 0.1f) continue;
            const glm::vec3 s = skyColor(clear, low, kEye, dir, 1e-4f);
            blue += c.b - c.r;
            clearBlue += s.b - s.r;
            ++gaps;
        }
        cloudBlue /= clouds;
        const double towardsClear = (blue / gaps - cloudBlue) / (clearBlue / gaps - cloudBlue);
        std::printf("cover %.2f (veil %.2f): %d gaps, their blue %.2f of the way from the clouds' to the clear "
                    "sky's; the most sunlight on the sea %.2f\n",
                    double(cover), double(cloudVeil(look)), gaps, towardsClear, double(sunniest));
        ASSERT_GT(gaps, 200) << "too few gaps to test, cover " << cover;
        if (cover < 0.7f) {
            EXPECT_GT(towardsClear, 0.95) << "fair weather's gaps are not the clear sky";
            EXPECT_GT(sunniest, 0.99f) << "no full sun under fair weather";
        } else {
            const double most = cover > 0.93f ? 0.15 : 0.5;
            EXPECT_LT(towardsClear, most) << "an overcast deck's gaps are blue, cover " << cover;
            EXPECT_LT(sunniest, 1.0f - 0.7f * cloudVeil(look) + 1e-4f)
                << "full sun under an overcast deck, cover " << cover;
        }
    }
}

constexpr int kW = 192, kH = 128;

/// How a drawn frame's pixels agree with the CPU's sky: those more than `tolerance` off the
/// colour expected and the most any is, and those the clouds changed, more than `changedBy` from
/// the same pixel under a clear sky.
struct Agreement {
    float tolerance, changedBy;
    int off = 0, changed = 0;
    float worst = 0.0f;
    void add(glm::vec3 drawn, glm::vec3 expected, glm::vec3 clear) {
        const float e = apart(drawn, expected);
        worst = std::max(worst, e);
        off += e > tolerance;
        changed += apart(drawn, clear) > changedBy;
    }
};

/// A camera 10 units up looking 40 degrees over the horizon, the sun low behind its left.
Camera skyCamera() {
    Camera camera;
    camera.position = {0.0f, 10.0f, 0.0f};
    camera.target = {0.0f, 10.0f + std::tan(0.7f), -1.0f};
    camera.fovY = 1.2f;
    camera.aspect = float(kW) / kH;
    return camera;
}

const DirectionalLight kSun{.direction = {-0.35f, 0.45f, -1.0f}, .color = {1.0f, 0.9f, 0.75f}};

TEST_F(Sky, TheSkyPassDrawsTheCpuSkyItsCloudsIncluded) {
    // Fair-weather cumulus, and an overcast deck with the veil in its gaps (cloudVeil 0.93).
    RenderTarget target(kW, kH);
    SurfaceRenderer renderer;
    const Camera camera = skyCamera();
    auto draw = [&](const WaterLook& l) {
        target.bind();
        target.clear();
        renderer.drawSky(camera, kSun, l);
        return target.readColor();
    };
    // Each pixel's direction, and its width as the shader takes it: the larger step to its
    // neighbours.
    auto dirAt = [&](double x, double y) {
        return glm::vec3(camera.rayThroughPixel(x + 0.5, kH - 1 - y + 0.5, kW, kH).direction);
    };
    for (const float cover : {0.45f, 0.95f}) {
        WaterLook look;
        look.cloudCover = cover;
        look.cloudScale = 2.0f;
        look.cloudDrift = {1.3f, 0.4f};
        const Image cloudy = draw(look);
        WaterLook clear = look;
        clear.cloudCover = 0.0f;
        const Image plain = draw(clear);
        Agreement sky{.tolerance = 2.5f / 255.0f, .changedBy = 10.0f / 255.0f};
        int clouded = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const glm::vec3 dir = dirAt(x, y);
                const float spread = std::max(glm::length(dirAt(x + 1, y) - dir), glm::length(dirAt(x, y + 1) - dir));
                sky.add(pixelOf(cloudy, x, y), displayValue(skyColor(look, kSun, camera.position, dir, spread)),
                        pixelOf(plain, x, y));
                clouded += cloudSample(look, camera.position, dir, spread).density > 0.5f;
                EXPECT_LE(apart(pixelOf(plain, x, y), displayValue(skyColor(clear, kSun, camera.position, dir, spread))),
                          1.5f / 255.0f);
            }
        std::printf("cover %.2f: %d of %d pixels clouded, %d changed by the clouds; %d off the CPU's sky by over "
                    "2.5/255 (at most %.1f/255)\n",
                    double(cover), clouded, kW * kH, sky.changed, sky.off, double(sky.worst) * 255.0);
        EXPECT_GT(clouded, kW * kH / 5) << "too few clouds to test, cover " << cover;
        EXPECT_GT(sky.changed, kW * kH / 5) << "the clouds do not show, cover " << cover;
        EXPECT_LE(sky.off, kW * kH / 200) << "the sky pass is not the CPU's sky, cover " << cover;
        EXPECT_LT(sky.worst, 12.0f / 255.0f) << "cover " << cover;
    }
}

/// A flat water plane 40 units across at y = 0 (the material's depth 0: its normals straight up)
/// showing only what a test asks of it (no glint, no haze), drawn with its look's clouds and under
/// a clear sky.
struct FlatWater {
    FlatWater(int width, int height) : target(width, height) {
        material.shading = Shading::Water;
        material.depthScale = 0.0f;
        material.water.glintStrength = 0.0f;
        material.water.hazeDistance = 1e9f;
    }
    /// (with the clouds, under a clear sky)
    std::pair<Image, Image> draw(const Camera& camera, const DirectionalLight& light) {
        auto one = [&](const SurfaceMaterial& m) {
            target.bind();
            target.clear();
            renderer.draw(plane, glm::mat4(1.0f), relief.textures, m, camera, light);
            return target.readColor();
        };
        SurfaceMaterial clear = material;
        clear.water.cloudCover = 0.0f;
        return {one(material), one(clear)};
    }
    /// A camera at `position` looking at `at`, with the render target's aspect, seeing past the
    /// plane's edge.
    Camera camera(glm::vec3 position, glm::vec3 at, float fovY) const {
        Camera c;
        c.position = position;
        c.target = at;
        c.fovY = fovY;
        c.aspect = float(target.width()) / float(target.height());
        c.farPlane = 100.0f;
        return c;
    }
    /// Calls visit(x, y, ray) for each pixel (x, y from the top) whose ray from `camera` goes down
    /// by more than `down` (its sine; the plane's far edge and the sky left out) and meets the
    /// plane within 19 units of its middle; returns how many it called it for.
    template <class Visit>
    int forEachWaterPixel(const Camera& camera, double down, Visit visit) const {
        const int w = target.width(), h = target.height();
        int pixels = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const Ray ray = camera.rayThroughPixel(x + 0.5, h - 1 - y + 0.5, w, h);
                if (!(ray.direction.y < -down)) continue;
                const glm::dvec3 hit = ray.origin + (-ray.origin.y / ray.direction.y) * ray.direction;
                if (std::abs(hit.x) > 19.0 || std::abs(hit.z) > 19.0) continue;
                ++pixels;
                visit(x, y, ray);
            }
        return pixels;
    }
    /// The sunlight the clouds let through (hfx::cloudSunlight) at the plane's point seen through
    /// pixel (x, y from the top) from `camera`, over the pixel's footprint there (the larger step
    /// to its neighbours' points).
    float cloudSunlightAt(const Camera& camera, const DirectionalLight& light, int x, int y) const {
        const int w = target.width(), h = target.height();
        auto hit = [&](int px, int py) {
            const Ray ray = camera.rayThroughPixel(px + 0.5, h - 1 - py + 0.5, w, h);
            return glm::vec3(ray.origin + (-ray.origin.y / ray.direction.y) * ray.direction);
        };
        const glm::vec3 p = hit(x, y);
        const float footprint = std::max(glm::length(hit(x + 1, y) - p), glm::length(hit(x, y + 1) - p));
        return cloudSunlight(material.water, light, p, footprint);
    }
    SurfaceMaterial material;
    RenderTarget target;
    SurfaceRenderer renderer;
    SineRelief relief{64, 0.05f};
    Mesh plane{makePlane({.size = 40.0f})};
};

TEST_F(Sky, AStillWaterMirrorsTheClouds) {
    // A mirror: water reflecting all of the sky (Fresnel 1), flat (the material's depth 0), no
    // glint or haze. Each pixel is the sky in its reflected direction, seen over the water's
    // floor of spread (2 mrad; its normals do not spread) and rolled off above the water's knee.
    FlatWater water(kW, kH);
    const Camera camera = water.camera({0.0f, 6.0f, 6.0f}, {0.0f, 0.0f, -4.0f}, 1.0f);
    SurfaceMaterial& material = water.material;
    material.water.fresnelF0 = 1.0f;
    material.water.cloudCover = 0.5f;
    material.water.cloudScale = 3.0f;
    const auto drawn = water.draw(camera, kSun);
    const auto &mirrored = drawn.first, &plain = drawn.second;
    Agreement mirror{.tolerance = 2.5f / 255.0f, .changedBy = 10.0f / 255.0f};
    int clouded = 0;
    const int pixels = water.forEachWaterPixel(camera, 0.05, [&](int x, int y, const Ray& ray) {
        const glm::vec3 reflected(glm::vec3(ray.direction.x, -ray.direction.y, ray.direction.z));
        mirror.add(pixelOf(mirrored, x, y),
                   displayValue(waterRollOff(skyColor(material.water, kSun, camera.position, reflected, 0.002f))),
                   pixelOf(plain, x, y));
        clouded += cloudSample(material.water, camera.position, reflected, 0.002f).density > 0.5f;
    });
    std::printf("%d water pixels, %d reflecting a cloud, %d changed by the clouds; %d off the CPU's mirrored sky by "
                "over 2.5/255 (at most %.1f/255)\n",
                pixels, clouded, mirror.changed, mirror.off, double(mirror.worst) * 255.0);
    ASSERT_GT(pixels, kW * kH / 2);
    EXPECT_GT(clouded, pixels / 5) << "too few clouds to test";
    EXPECT_GT(mirror.changed, pixels / 5) << "the water does not reflect the clouds";
    EXPECT_LE(mirror.off, pixels / 200) << "the water does not mirror the CPU's sky";
    EXPECT_LT(mirror.worst, 12.0f / 255.0f);
}

TEST_F(Sky, TheSeaFadesIntoTheCloudsGreyAtTheHorizonUnderOvercast) {
    // Water all haze (half its colour haze 0.05 units off): each pixel is the sky at the horizon
    // in the direction of its point, as the CPU's sky has it, under 0.9 of cloud the clouds' grey
    // and not the clear sky's pale blue (which the haze was before the horizon took the clouds).
    FlatWater water(kW, kH);
    const Camera camera = water.camera({0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, -20.0f}, 0.8f);
    SurfaceMaterial& material = water.material;
    material.water.cloudCover = 0.9f;
    material.water.hazeDistance = 0.05f;
    const auto drawn = water.draw(camera, kSun);
    const auto &overcast = drawn.first, &plain = drawn.second;
    Agreement haze{.tolerance = 3.0f / 255.0f, .changedBy = 20.0f / 255.0f};
    const int pixels = water.forEachWaterPixel(camera, 0.02, [&](int x, int y, const Ray& ray) {
        const glm::vec3 level = glm::normalize(glm::vec3(float(ray.direction.x), 0.0f, float(ray.direction.z)));
        haze.add(pixelOf(overcast, x, y),
                 displayValue(waterRollOff(skyColor(material.water, kSun, camera.position, level, 0.0f))),
                 pixelOf(plain, x, y));
    });
    std::printf("%d water pixels, %d changed by the clouds; %d off the CPU's horizon by over 3/255 (at most %.1f/255)\n",
                pixels, haze.changed, haze.off, double(haze.worst) * 255.0);
    ASSERT_GT(pixels, kW * kH / 3);
    EXPECT_GT(haze.changed, pixels * 9 / 10) << "the haze is the clear sky's under overcast";
    EXPECT_LE(haze.off, pixels / 200) << "the haze is not the CPU's horizon";
}

TEST_F(Sky, TheCloudsShadowsDimTheSunsLightOnTheWater) {
    // Water seen from straight above, lit by the sun alone (no ambient light), reflecting nothing
    // (Fresnel 0 head-on, no glint, no haze): each pixel is its body colour times the sun's light,
    // so the pixel with clouds over the pixel under a clear sky is the sunlight the clouds let
    // through there, hfx::cloudSunlight at its point (the layer 20 units up: shadows of about 13).
    const int n = 160;
    FlatWater water(n, n);
    Camera camera = water.camera({0.0f, 30.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 1.0f);
    camera.up = {0.0f, 0.0f, -1.0f};
    const DirectionalLight sun{.direction = {0.3f, 1.0f, 0.2f}, .color = glm::vec3(4.0f), .ambient = glm::vec3(0.0f)};
    SurfaceMaterial& material = water.material;
    material.water.fresnelF0 = 0.0f;
    material.water.translucency = 0.0f;
    material.water.cloudHeight = 20.0f;
    material.water.cloudDrift = {0.4f, -0.3f};
    // Fair-weather cumulus, and an overcast deck whose veil dims the sun in its gaps (cloudVeil
    // 0.74, its thickness half the deck's mean 0.69: there 1 - 0.74 (0.7 + 0.25 x 0.345) = 0.42).
    for (const float cover : {0.6f, 0.9f}) {
        material.water.cloudCover = cover;
        const auto [clouded, plain] = water.draw(camera, sun);
        int checked = 0, off = 0, shaded = 0, sunny = 0, veiled = 0;
        double worst = 0.0;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const float bright = std::pow(pixelOf(plain, x, y).z, 2.2f); // blue: the water's brightest
                if (bright < 0.05f) continue;
                ++checked;
                const float expected = water.cloudSunlightAt(camera, sun, x, y);
                const double e = std::abs(std::pow(pixelOf(clouded, x, y).z, 2.2f) / bright - expected);
                worst = std::max(worst, e);
                off += e > 0.04;
                shaded += expected < 0.3f;
                sunny += expected > 0.95f;
                veiled += expected > 0.4f && expected < 0.44f;
            }
        std::printf("cover %.1f: %d pixels checked: %d in a cloud's shadow, %d in full sun, %d under the veil alone; %d "
                    "off the CPU's sunlight by over 0.04 (at most %.3f)\n",
                    double(cover), checked, shaded, sunny, veiled, off, worst);
        ASSERT_GT(checked, n * n / 2);
        EXPECT_GT(shaded, checked / 6) << "too few shadows to test, cover " << cover;
        EXPECT_GT(cover < 0.7f ? sunny : veiled, checked / 20) << "too little sun to test, cover " << cover;
        EXPECT_LE(off, checked / 100) << "the water's sunlight is not the CPU's under the clouds, cover " << cover;
        EXPECT_LT(worst, 0.1) << "cover " << cover;
    }

    // A deferred engine lights the water itself: the material output's light share (b) is the
    // same sunlight (the flat water casts no self-shadow), in float, as precisely as the hash.
    RenderTarget deferred(n, n, true);
    deferred.bind();
    deferred.clear();
    water.renderer.setSurfaceOutputs({.material = 1});
    water.renderer.draw(water.plane, glm::mat4(1.0f), water.relief.textures, material, camera, sun);
    water.renderer.setSurfaceOutputs({});
    const std::vector<glm::vec4> channels = deferred.readTrace(); // (draw buffer 1, bottom row first)
    int lightOff = 0;
    double worstLight = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double e = std::abs(channels[size_t(n - 1 - y) * n + x].z - water.cloudSunlightAt(camera, sun, x, y));
            worstLight = std::max(worstLight, e);
            lightOff += e > 0.01;
        }
    std::printf("the material output's light: %d of %d pixels off the CPU's sunlight by over 0.01 (at most %.3f)\n",
                lightOff, n * n, worstLight);
    EXPECT_LE(lightOff, n * n / 200);
    EXPECT_LT(worstLight, 0.1);
}

TEST_F(Sky, TheCloudsShadowsDimTheGlowThroughTheWater) {
    // Flat water seen at a grazing angle towards a low sun, reflecting a black clear sky (and at
    // this angle some of the clouds): the translucency's glow (the frame with it less the frame
    // without, in linear light) is the sun's, scattered out of the water, so a cloud's shadow
    // dims it as it dims the sun: with the clouds over the glow under a clear sky, each pixel's
    // share is hfx::cloudSunlight at its point.
    const int n = 160;
    FlatWater water(n, n);
    const Camera camera = water.camera({0.0f, 3.0f, 0.0f}, {0.0f, 0.0f, -20.0f}, 0.8f);
    const DirectionalLight sun{.direction = {0.1f, 0.3f, -1.0f}, .color = glm::vec3(4.0f), .ambient = glm::vec3(0.0f)};
    SurfaceMaterial& material = water.material;
    material.water.fresnelF0 = 0.0f;
    material.water.skyZenith = material.water.skyHorizon = glm::vec3(0.0f); // the reflection adds nothing
    material.water.sunGlow = 0.0f;
    material.water.cloudCover = 0.6f;
    material.water.cloudHeight = 4.0f; // low, so that the low sun's shadows fall near their clouds
    material.water.cloudScale = 2.0f;
    material.water.translucency = 1.0f;
    const auto [clouded, plain] = water.draw(camera, sun);
    material.water.translucency = 0.0f;
    const auto [cloudedDark, plainDark] = water.draw(camera, sun);
    auto seenZ = [&](int x, int y) { // where the plane's point seen through pixel (x, y from the top) lies
        const Ray ray = camera.rayThroughPixel(x + 0.5, n - 1 - y + 0.5, n, n);
        return ray.origin.z + (-ray.origin.y / ray.direction.y) * ray.direction.z;
    };
    auto linearGreen = [](const Image& image, int x, int y) { return std::pow(pixelOf(image, x, y).y, 2.2f); };
    int checked = 0, off = 0, shaded = 0, sunny = 0, clipped = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float clearGlow = linearGreen(plain, x, y) - linearGreen(plainDark, x, y);
            if (clearGlow < 0.05f || seenZ(x, y) > -1.0) continue; // the glow's faint edge; the sky
            // Where the clouds' reflection brings a pixel to the display's white, what the glow
            // adds is clipped: no share can be read there.
            if (pixelOf(clouded, x, y).y > 0.94f) {
                ++clipped;
                continue;
            }
            ++checked;
            const float expected = water.cloudSunlightAt(camera, sun, x, y);
            const float share = (linearGreen(clouded, x, y) - linearGreen(cloudedDark, x, y)) / clearGlow;
            off += std::abs(share - expected) > 0.1f;
            shaded += expected < 0.7f;
            sunny += expected > 0.95f;
        }
    std::printf("%d glowing pixels checked (%d clipped left out): %d in a cloud's shadow, %d in full sun; %d off the "
                "CPU's sunlight by over 0.1\n",
                checked, clipped, shaded, sunny, off);
    ASSERT_GT(checked, n * n / 8);
    EXPECT_GT(shaded, checked / 10) << "too few shadows to test";
    EXPECT_GT(sunny, checked / 10) << "too little sun to test";
    EXPECT_LE(off, checked / 50) << "the glow is not the sunlight the clouds let through";
}

TEST_F(Sky, BadCloudsAreRefusedByNameAndDrawNothing) {
    RenderTarget target(kW, kH);
    SurfaceRenderer renderer;
    const Camera camera = skyCamera();
    target.bind();
    target.clear();
    renderer.drawSky(camera, kSun, WaterLook{});
    const Image before = target.readColor();
    GlTexture image = GlTexture::create();
    glTextureStorage2D(image.id(), 1, GL_RGB32F, 8, 4);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Case {
        const char* what;
        WaterLook look;
        const char* named;
    };
    auto with = [](auto change) {
        WaterLook look;
        look.cloudCover = 0.4f;
        change(look);
        return look;
    };
    const Case cases[] = {
        {"a cover over 1", with([](WaterLook& l) { l.cloudCover = 1.5f; }), "WaterLook.cloudCover"},
        {"a negative cover", with([](WaterLook& l) { l.cloudCover = -0.1f; }), "WaterLook.cloudCover"},
        {"a cover that is not a number", with([&](WaterLook& l) { l.cloudCover = nan; }), "WaterLook.cloudCover"},
        {"a scale of 0", with([](WaterLook& l) { l.cloudScale = 0.0f; }), "WaterLook.cloudScale"},
        {"a scale over 64", with([](WaterLook& l) { l.cloudScale = 100.0f; }), "WaterLook.cloudScale"},
        {"a drift not finite", with([&](WaterLook& l) { l.cloudDrift.y = nan; }), "WaterLook.cloudDrift"},
        {"a height of 0", with([](WaterLook& l) { l.cloudHeight = 0.0f; }), "WaterLook.cloudHeight"},
        {"a height not finite", with([](WaterLook& l) { l.cloudHeight = std::numeric_limits<float>::infinity(); }),
         "WaterLook.cloudHeight"},
        {"clouds with an environment image", with([&](WaterLook& l) { l.environment = image.id(); }), "environment image"},
    };
    SurfaceMaterial material;
    material.shading = Shading::Water;
    const SineRelief relief(64, 0.05f);
    const Mesh plane(makePlane({.size = 40.0f}));
    for (const Case& c : cases) {
        const std::string sky = messageOf([&] { renderer.drawSky(camera, kSun, c.look); });
        EXPECT_NE(sky.find(c.named), std::string::npos) << c.what << ": " << sky;
        material.water = c.look;
        const std::string draw = messageOf([&] { renderer.draw(plane, glm::mat4(1.0f), relief.textures, material, camera, kSun); });
        EXPECT_NE(draw.find(c.named), std::string::npos) << c.what << ": " << draw;
        EXPECT_EQ(target.readColor().pixels, before.pixels) << c.what << " drew";
    }
}

} // namespace
} // namespace hfx::test
