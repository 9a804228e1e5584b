#include "support/Fields.h"


#include <algorithm>
#include <cmath>
#include <numbers>

namespace hfx::test {

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
    const Ray ray = camera.rayThroughPixel(x + 0.5, y + 0.5, width, height);
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

Camera cameraAtAngle(double angleDegrees, float distance, float aspect) {
    const float elevation = float((90.0 - angleDegrees) * std::numbers::pi / 180.0);
    Camera c = Camera::orbit({0, 0, 0}, distance, 0.3f, elevation);
    if (angleDegrees < 1.0) c.up = {0, 0, -1}; // looking straight down
    c.aspect = aspect;
    c.fovY = 0.35f;
    c.nearPlane = 0.05f;
    c.farPlane = 50.0f;
    return c;
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

} // namespace hfx::test
