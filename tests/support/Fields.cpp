#include "support/Fields.h"

#include "support/References.h"

#include "hfx/core/Image.h"
#include "hfx/tools/AccuracyProbe.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hfx::test {

SineRelief::SineRelief(int field, float depthScale)
    : heights(sumOfSines(field, {{0.3, 2, 1, 0.0}, {0.15, -1, 2, 0.7}})),
      textures({.width = field, .height = field, .mipmaps = false, .normalDepth = depthScale}) {
    textures.uploadTexels(sobelReference(heights, field, depthScale).data());
    textures.setAlbedo(Image{1, 1, 3, {0.5f, 0.5f, 0.5f}});
}

std::vector<float> sumOfSines(int size, const std::vector<SineTerm>& terms) {
    std::vector<float> h(size_t(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double v = 0.5;
            for (const SineTerm& t : terms)
                v += t.amplitude *
                     std::sin(2 * std::numbers::pi * (t.m * x + t.n * y) / size + t.phase);
            h[size_t(y) * size + x] = float(v);
        }
    return h;
}

std::vector<float> blocks(int size, int blocksPerEdge) {
    std::vector<float> h(size_t(size) * size);
    const int cell = size / blocksPerEdge, mortar = std::max(1, cell / 8);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool inMortar = (x % cell) < mortar || (y % cell) < mortar;
            h[size_t(y) * size + x] = inMortar ? 0.1f : 0.9f;
        }
    return h;
}

bool PlaneView::pixelRay(int x, int y, int width, int height, glm::dvec2& uv0,
                         glm::dvec3& toEye) const {
    return planePixelRay(camera, planeSize, x, y, width, height, uv0, toEye);
}

Camera cameraAtAngle(double angleDegrees, float distance, float aspect) {
    return accuracyCamera(angleDegrees, distance, aspect);
}

glm::mat4 obliqueNearPlane(glm::mat4 projection, const glm::vec4& plane) {
    const glm::vec4 corner((std::copysign(1.0f, plane.x) + projection[2][0]) / projection[0][0],
                           (std::copysign(1.0f, plane.y) + projection[2][1]) / projection[1][1], -1.0f,
                           (1.0f + projection[2][2]) / projection[3][2]);
    const glm::vec4 c = plane * (2.0f / glm::dot(plane, corner));
    projection[0][2] = c.x;
    projection[1][2] = c.y;
    projection[2][2] = c.z + 1.0f;
    projection[3][2] = c.w;
    return projection;
}

ErrorStats statistics(std::vector<double> errors) {
    ErrorStats s;
    s.count = errors.size();
    if (errors.empty()) return s;
    std::sort(errors.begin(), errors.end());
    double sum = 0;
    for (double e : errors) sum += e;
    s.mean = sum / errors.size();
    s.p95 = errors[std::min(errors.size() - 1, size_t(0.95 * errors.size()))];
    s.max = errors.back();
    return s;
}

float displayValue(float linear) { return std::pow(std::clamp(linear, 0.0f, 1.0f), 1.0f / 2.2f); }
glm::vec3 displayValue(glm::vec3 linear) {
    return {displayValue(linear.x), displayValue(linear.y), displayValue(linear.z)};
}

float waterRollOff(float linear) {
    const float knee = 0.75f;
    return std::min(linear, knee) + (1.0f - knee) * (1.0f - std::exp(-std::max(linear - knee, 0.0f) / (1.0f - knee)));
}
glm::vec3 waterRollOff(glm::vec3 linear) {
    return {waterRollOff(linear.x), waterRollOff(linear.y), waterRollOff(linear.z)};
}

} // namespace hfx::test
