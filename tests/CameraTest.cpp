// The camera's screen area of a polygon (what the demo weighs the texel shadows' pass against):
// against the analytic area of a square facing the camera, and against counting the pixels whose
// centre ray meets the polygon, for quads crossing the near plane and the image's edges, in either
// depth convention; the reversed-Z projection; and the camera's own check of its fields.

#include "support/Fields.h"
#include "support/Fixtures.h"

#include "hfx/core/Camera.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

namespace hfx::test {
namespace {

constexpr int kWidth = 320, kHeight = 180;

Camera lookingDownMinusZ() {
    Camera c;
    c.position = {0.0f, 0.0f, 0.0f};
    c.target = {0.0f, 0.0f, -1.0f};
    c.aspect = float(kWidth) / float(kHeight);
    return c;
}

std::array<glm::vec3, 4> square(glm::vec3 centre, float half) {
    return {centre + glm::vec3(-half, -half, 0.0f), centre + glm::vec3(half, -half, 0.0f),
            centre + glm::vec3(half, half, 0.0f), centre + glm::vec3(-half, half, 0.0f)};
}

/// Pixel centres whose ray meets the convex quad (corners in order, one plane).
int pixelsHit(const Camera& camera, const std::array<glm::vec3, 4>& quad) {
    const glm::dvec3 a(quad[0]), n = glm::normalize(glm::cross(glm::dvec3(quad[1]) - a, glm::dvec3(quad[2]) - a));
    int count = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const Ray ray = camera.rayThroughPixel(x + 0.5, y + 0.5, kWidth, kHeight);
            const double denominator = glm::dot(ray.direction, n);
            if (std::abs(denominator) < 1e-12) continue;
            const double t = glm::dot(a - ray.origin, n) / denominator;
            if (t <= camera.nearPlane) continue;
            const glm::dvec3 p = ray.origin + ray.direction * t;
            bool inside = true;
            for (int i = 0; i < 4; ++i) {
                const glm::dvec3 e0(quad[i]), e1(quad[(i + 1) % 4]);
                if (glm::dot(glm::cross(e1 - e0, p - e0), n) < 0.0) inside = false;
            }
            count += inside;
        }
    return count;
}

TEST(ScreenArea, ASquareFacingTheCameraCoversItsProjectedArea) {
    const Camera camera = lookingDownMinusZ();
    const float distance = 5.0f, half = 0.5f;
    const double t = std::tan(camera.fovY / 2.0);
    const double hy = half / (distance * t), hx = hy / camera.aspect; // half extents in NDC
    const double expected = hx * hy * kWidth * kHeight;
    const auto quad = square({0.0f, 0.0f, -distance}, half);
    EXPECT_NEAR(screenArea(quad, camera.viewProjection(), kWidth, kHeight), expected, 1e-6 * expected);
    // Shifted right by its own half width in NDC terms: the image's edge cuts off half of it.
    const float shift = float(1.0 * distance * t * camera.aspect); // NDC x = 1
    const auto halfOff = square({shift, 0.0f, -distance}, half);
    EXPECT_NEAR(screenArea(halfOff, camera.viewProjection(), kWidth, kHeight), expected / 2.0, 1e-4 * expected);
}

TEST(ScreenArea, AQuadLargerThanTheViewCoversTheWholeImageAndOneBehindTheCameraNothing) {
    const Camera camera = lookingDownMinusZ();
    EXPECT_NEAR(screenArea(square({0.0f, 0.0f, -2.0f}, 50.0f), camera.viewProjection(), kWidth, kHeight),
                double(kWidth) * kHeight, 1e-6 * kWidth * kHeight);
    EXPECT_EQ(screenArea(square({0.0f, 0.0f, 3.0f}, 1.0f), camera.viewProjection(), kWidth, kHeight), 0.0);
    EXPECT_EQ(screenArea(square({40.0f, 0.0f, -2.0f}, 1.0f), camera.viewProjection(), kWidth, kHeight), 0.0);
}

TEST(ScreenArea, AgreesWithThePixelsWhoseRayMeetsAQuadThroughTheNearPlaneAndTheEdges) {
    // An orbiting camera over floors that run from behind it to past the image's edges, and a
    // tilted quad: the area counted by rays agrees within the pixels along the outline.
    const Camera camera = [] {
        Camera c = Camera::orbit({0.0f, 0.0f, 0.0f}, 3.0f, 0.4f, 0.5f);
        c.aspect = float(kWidth) / float(kHeight);
        return c;
    }();
    const std::array<glm::vec3, 4> quads[] = {
        {glm::vec3(-2, 0, 2), glm::vec3(2, 0, 2), glm::vec3(2, 0, -2), glm::vec3(-2, 0, -2)},     // in view
        {glm::vec3(-20, 0, 20), glm::vec3(20, 0, 20), glm::vec3(20, 0, -20), glm::vec3(-20, 0, -20)}, // past it
        {glm::vec3(-1, -1, 0), glm::vec3(1.5f, -0.5f, 0.3f), glm::vec3(1, 1, 0.5f), glm::vec3(-1.5f, 0.5f, 0.2f)},
    };
    for (const bool reversed : {false, true})
        for (const auto& quad : quads) {
            Camera c = camera;
            c.reversedZ = reversed; // the near plane at clip depth 1, not -1: clipped there too
            const double area = screenArea(quad, c.viewProjection(), kWidth, kHeight);
            const int hits = pixelsHit(c, quad);
            ASSERT_GT(hits, 1000);
            EXPECT_NEAR(area, double(hits), 0.01 * hits)
                << "quad from (" << quad[0].x << ", " << quad[0].z << ")" << (reversed ? ", reversed Z" : "");
        }
}

TEST(Camera, AReversedZProjectionPutsTheNearPlaneAtOneAndTheFarAtZero) {
    // The same image (x, y and the rays through pixels, jitter included), the depth reversed onto
    // GL's [0, 1] clip depth; the default keeps [-1, 1] with the near plane at -1.
    Camera standard = Camera::orbit({0.0f, 0.0f, 0.0f}, 3.0f, 0.4f, 0.5f);
    standard.nearPlane = 0.1f;
    standard.farPlane = 50.0f;
    standard.jitter = {0.003f, -0.002f};
    Camera reversed = standard;
    reversed.reversedZ = true;
    const glm::vec3 forward = glm::normalize(standard.target - standard.position);
    const glm::vec3 aside = glm::normalize(glm::cross(forward, standard.up));
    auto ndc = [](const Camera& c, glm::vec3 p) {
        const glm::vec4 clip = c.viewProjection() * glm::vec4(p, 1.0f);
        return glm::vec3(clip) / clip.w;
    };
    for (const float distance : {0.1f, 0.7f, 3.0f, 50.0f}) {
        const glm::vec3 p = standard.position + forward * distance + aside * (0.2f * distance);
        const glm::vec3 a = ndc(standard, p), b = ndc(reversed, p);
        EXPECT_NEAR(a.x, b.x, 1e-5f) << distance;
        EXPECT_NEAR(a.y, b.y, 1e-5f) << distance;
        const double n = standard.nearPlane, f = standard.farPlane;
        EXPECT_NEAR(a.z, (f + n - 2.0 * n * f / distance) / (f - n), 1e-4) << distance;
        EXPECT_NEAR(b.z, n * (f - distance) / (distance * (f - n)), 1e-5) << distance;
    }
    EXPECT_NEAR(ndc(reversed, standard.position + forward * 0.1f).z, 1.0f, 1e-5f);
    EXPECT_NEAR(ndc(reversed, standard.position + forward * 50.0f).z, 0.0f, 1e-5f);
    for (const glm::dvec2 pixel : {glm::dvec2(0.5, 0.5), glm::dvec2(160.5, 90.5), glm::dvec2(319.5, 10.5)}) {
        const Ray r0 = standard.rayThroughPixel(pixel.x, pixel.y, kWidth, kHeight);
        const Ray r1 = reversed.rayThroughPixel(pixel.x, pixel.y, kWidth, kHeight);
        EXPECT_LT(glm::length(r0.direction - r1.direction), 1e-6) << pixel.x << ", " << pixel.y;
    }
}

TEST(Camera, AnEnginesMatricesMakeTheSameCamera) {
    // Camera::fromMatrices: an engine's view and projection give back the camera they came from,
    // in either depth convention; the near plane's reach is the lens's (near * the corner's secant).
    // The lens is not Camera's default, so a projection taken from the fields would show.
    for (const bool reversed : {false, true}) {
        Camera c = Camera::orbit({0.3f, 0.0f, -0.2f}, 3.0f, 0.4f, 0.5f);
        c.fovY = 1.1f;
        c.aspect = 1.5f;
        c.nearPlane = 0.05f;
        c.farPlane = 30.0f;
        c.reversedZ = reversed;
        const Camera engine = Camera::fromMatrices(c.view(), c.projection(), reversed);
        EXPECT_NO_THROW(engine.validate());
        for (int col = 0; col < 4; ++col) {
            EXPECT_LT(glm::length(engine.view()[col] - c.view()[col]), 1e-5f) << col;
            EXPECT_EQ(engine.projection()[col], c.projection()[col]) << col;
        }
        const Ray a = c.rayThroughPixel(10.5, 170.5, kWidth, kHeight), b = engine.rayThroughPixel(10.5, 170.5, kWidth, kHeight);
        EXPECT_LT(glm::length(a.direction - b.direction), 1e-5);
        const double t = std::tan(c.fovY / 2.0);
        EXPECT_NEAR(engine.nearPlaneReach(), c.nearPlane * std::sqrt(1.0 + t * t * (1.0 + c.aspect * c.aspect)), 1e-6);
        EXPECT_NEAR(c.nearPlaneReach(), engine.nearPlaneReach(), 1e-7);
    }
}

TEST(Camera, AMirrorsViewMakesAMirroredCameraWithItsEyeAndRays) {
    // An engine's planar reflection: its view times a reflection about the water's plane (y = 0.2),
    // a determinant of -1. fromMatrices keeps the matrix (the image flipped left to right, where a
    // look-at lens would draw the unmirrored one) and the eye it gives, the camera's reflected
    // through the plane; each pixel's ray is the camera's reflected.
    const Camera c = Camera::orbit({0.3f, 0.0f, -0.2f}, 3.0f, 0.4f, 0.5f);
    const glm::mat4 reflect = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.2f, 0.0f)) *
                              glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -1.0f, 1.0f)) *
                              glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.2f, 0.0f));
    const Camera mirror = Camera::fromMatrices(c.view() * reflect, c.projection());
    EXPECT_NO_THROW(mirror.validate());
    EXPECT_TRUE(mirror.mirrored);
    EXPECT_FALSE(Camera::fromMatrices(c.view(), c.projection()).mirrored);
    for (int col = 0; col < 4; ++col) EXPECT_LT(glm::length(mirror.view()[col] - (c.view() * reflect)[col]), 1e-5f) << col;
    EXPECT_LT(glm::length(mirror.position - glm::vec3(c.position.x, 0.4f - c.position.y, c.position.z)), 1e-5f);
    for (const glm::dvec2 pixel : {glm::dvec2(10.5, 170.5), glm::dvec2(200.5, 20.5)}) {
        const Ray a = c.rayThroughPixel(pixel.x, pixel.y, kWidth, kHeight),
                  b = mirror.rayThroughPixel(pixel.x, pixel.y, kWidth, kHeight);
        EXPECT_LT(glm::length(glm::dvec3(a.direction.x, -a.direction.y, a.direction.z) - b.direction), 1e-5);
    }
    // A view that scales, shears or projects has no eye that draws what it draws: refused by name.
    for (const glm::mat4& bad : {c.view() * glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)),
                                 c.view() * glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0.5f, 1, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, 0, 0, 1)),
                                 c.projection() * c.view()})
        EXPECT_NE(messageOf([&] { (void)Camera::fromMatrices(bad, c.projection()); }).find("the view must be rigid"), std::string::npos);
    glm::mat4 nan = c.view();
    nan[3][0] = std::nanf("");
    EXPECT_NE(messageOf([&] { (void)Camera::fromMatrices(nan, c.projection()); }).find("the view must be finite"), std::string::npos);
}

TEST(Camera, AnObliqueNearPlaneKeepsEveryPixelsRay) {
    // A planar reflection's projection, its near plane on the water (obliqueNearPlane): the far
    // plane tilts behind the eye for some rays, yet every pixel's ray is the plain projection's.
    const Camera c = Camera::orbit({0.0f, 0.2f, 0.0f}, 3.0f, 0.4f, 0.25f);
    const glm::mat4 mirrorView = c.view() * glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -1.0f, 1.0f));
    const glm::vec4 water = glm::transpose(glm::inverse(mirrorView)) * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
    const Camera plain = Camera::fromMatrices(mirrorView, c.projection());
    const Camera clipped = Camera::fromMatrices(mirrorView, obliqueNearPlane(c.projection(), water));
    EXPECT_NO_THROW(clipped.validate());
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(clipped.viewProjection()));
    int behind = 0;
    double worst = 0.0;
    for (int y = 0; y < kHeight; y += 8)
        for (int x = 0; x < kWidth; x += 8) {
            const double px = x + 0.5, py = y + 0.5;
            behind += (inverse * glm::dvec4(2.0 * px / kWidth - 1.0, 2.0 * py / kHeight - 1.0, 1.0, 1.0)).w < 0.0;
            const Ray a = plain.rayThroughPixel(px, py, kWidth, kHeight), b = clipped.rayThroughPixel(px, py, kWidth, kHeight);
            worst = std::max(worst, glm::length(a.direction - b.direction));
        }
    EXPECT_GT(behind, 0) << "no far point behind the eye: the case is not tried";
    EXPECT_LT(worst, 1e-5);
}

TEST(Camera, AnOrthographicCamerasRaysRunAlongItsAxisFromTheNearPlane) {
    // glm::ortho through an engine's matrices: every pixel's ray has the view axis's direction
    // and starts on the near plane, where the pixel lies across it.
    const Camera lens = Camera::orbit({0.2f, 0.0f, -0.1f}, 4.0f, 0.4f, 0.7f);
    const Camera c = Camera::fromMatrices(lens.view(), glm::ortho(-2.0f, 2.0f, -1.5f, 1.5f, 0.5f, 20.0f));
    EXPECT_NO_THROW(c.validate());
    EXPECT_TRUE(c.orthographic());
    EXPECT_FALSE(lens.orthographic());
    const glm::dvec3 forward = glm::normalize(glm::dvec3(lens.target - lens.position));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(lens.up))), up = glm::cross(right, forward);
    for (const glm::dvec2 pixel : {glm::dvec2(0.5, 0.5), glm::dvec2(100.5, 70.25), glm::dvec2(kWidth - 0.5, kHeight - 0.5)}) {
        const Ray r = c.rayThroughPixel(pixel.x, pixel.y, kWidth, kHeight);
        EXPECT_LT(glm::length(r.direction - forward), 1e-6);
        const glm::dvec2 ndc = 2.0 * pixel / glm::dvec2(kWidth, kHeight) - 1.0;
        const glm::dvec3 expected = glm::dvec3(lens.position) + 0.5 * forward + 2.0 * ndc.x * right + 1.5 * ndc.y * up;
        EXPECT_LT(glm::length(r.origin - expected), 1e-5) << pixel.x << ", " << pixel.y;
    }
}

TEST(Camera, ACustomProjectionThatIsNeitherPerspectiveNorOrthographicIsRefusedByName) {
    const Camera usual = Camera::orbit({0.0f, 0.0f, 0.0f}, 3.0f, 0.4f, 0.5f);
    auto refusal = [&](const glm::mat4& projection, bool reversed) {
        Camera c = usual;
        c.customProjection = projection;
        c.reversedZ = reversed;
        return messageOf([&] { c.validate(); });
    };
    const glm::mat4 offAxis = glm::frustum(-0.01f, 0.03f, -0.01f, 0.012f, 0.02f, 50.0f);
    EXPECT_EQ(refusal(offAxis, false), "(no error)");
    EXPECT_EQ(refusal(glm::frustumRH_ZO(-0.01f, 0.03f, -0.01f, 0.012f, 50.0f, 0.02f), true), "(no error)");
    EXPECT_EQ(refusal(glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f), false), "(no error)");
    EXPECT_EQ(refusal(glm::orthoRH_ZO(-1.0f, 1.0f, -1.0f, 1.0f, 10.0f, 0.1f), true), "(no error)");
    EXPECT_NE(refusal(glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f), true).find("but Camera.reversedZ is true"),
              std::string::npos);
    glm::mat4 skewed = offAxis; // a last row of neither kind
    skewed[0][3] = 0.1f;
    EXPECT_NE(refusal(skewed, false).find("must be a perspective projection, its last row (0, 0, -1, 0)"), std::string::npos);
    glm::mat4 nan = offAxis;
    nan[2][0] = std::nanf("");
    EXPECT_NE(refusal(nan, false).find("Camera.customProjection must be finite"), std::string::npos);
    glm::mat4 flat = offAxis;
    flat[0][0] = 0.0f;
    EXPECT_NE(refusal(flat, false).find("has no inverse"), std::string::npos);
    EXPECT_NE(refusal(offAxis, true).find("maps depth GL's default way (near at the smaller depth), but Camera.reversedZ is true"),
              std::string::npos);
}

TEST(Camera, ABadFieldIsRefusedByNameAndTheUsualViewsPass) {
    // Camera::validate, which every draw calls first: each of these makes the view or the
    // projection a NaN (lookAt with no direction or no roll) or turns the image inside out.
    EXPECT_NO_THROW(Camera{}.validate());
    EXPECT_NO_THROW(lookingDownMinusZ().validate());
    EXPECT_NO_THROW(Camera::orbit({1.0f, 2.0f, 3.0f}, 4.0f, 0.3f, 1.5f).validate());
    Camera down = Camera::orbit({0.0f, 0.0f, 0.0f}, 2.0f, 0.3f, 1.5707964f);
    down.up = {0.0f, 0.0f, -1.0f}; // straight down, rolled as the accuracy camera is
    EXPECT_NO_THROW(down.validate());
    struct Case {
        void (*spoil)(Camera&);
        const char* expected;
    };
    const Case cases[] = {
        {[](Camera& c) { c.position.x = std::nanf(""); }, "Camera.position must be finite, got (nan, 0, 0)"},
        {[](Camera& c) { c.target.z = -INFINITY; }, "Camera.target must be finite, got (0, 0, -inf)"},
        {[](Camera& c) { c.up = glm::vec3(std::nanf("")); }, "Camera.up must be finite, got (nan, nan, nan)"},
        {[](Camera& c) { c.jitter.y = INFINITY; }, "Camera.jitter must be finite, got (0, inf)"},
        {[](Camera& c) { c.target = c.position; }, "Camera.position (0, 0, 0) is its target: no view direction"},
        {[](Camera& c) { c.up = {0.0f, 0.0f, 2.0f}; }, "Camera.up (0, 0, 2) is not across the view direction (0, 0, -1)"},
        {[](Camera& c) { c.up = glm::vec3(0.0f); }, "Camera.up (0, 0, 0) is not across the view direction"},
        {[](Camera& c) { c.fovY = 0.0f; }, "Camera.fovY must be in (0, pi) radians, got 0"},
        {[](Camera& c) { c.fovY = 3.5f; }, "Camera.fovY must be in (0, pi) radians, got 3.5"},
        {[](Camera& c) { c.aspect = -1.0f; }, "Camera.aspect must be positive, got -1"},
        {[](Camera& c) { c.nearPlane = 0.0f; }, "Camera needs 0 < nearPlane < farPlane, both finite, got 0 and 100"},
        {[](Camera& c) { c.farPlane = 0.001f; }, "Camera needs 0 < nearPlane < farPlane, both finite, got 0.01 and 0.001"},
        {[](Camera& c) { c.farPlane = INFINITY; }, "Camera needs 0 < nearPlane < farPlane, both finite, got 0.01 and inf"},
    };
    for (const Case& c : cases) {
        Camera camera = lookingDownMinusZ();
        c.spoil(camera);
        const std::string message = messageOf([&] { camera.validate(); });
        EXPECT_EQ(message.substr(0, std::string(c.expected).size()), c.expected) << message;
    }
}

} // namespace
} // namespace hfx::test
