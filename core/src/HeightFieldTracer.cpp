#include "hfx/core/HeightFieldTracer.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hfx {

HeightFieldTracer::HeightFieldTracer(std::vector<float> heights, int width, int height,
                                     EdgeMode edges)
    : heights_(std::move(heights)), width_(width), height_(height), edges_(edges) {
    if (width < 1 || height < 1 || heights_.size() != size_t(width) * size_t(height))
        throw Error(str("HeightFieldTracer: ", heights_.size(), " samples do not make a ", width,
                        "x", height, " field"));
}

double HeightFieldTracer::sample(long long i, long long j) const {
    i = wrapsU(edges_) ? ((i % width_) + width_) % width_ : std::clamp<long long>(i, 0, width_ - 1);
    j = wrapsV(edges_) ? ((j % height_) + height_) % height_ : std::clamp<long long>(j, 0, height_ - 1);
    return heights_[size_t(j) * width_ + size_t(i)];
}

double HeightFieldTracer::heightAt(glm::dvec2 uv) const {
    const double x = uv.x * width_ - 0.5, y = uv.y * height_ - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const auto i = static_cast<long long>(fx), j = static_cast<long long>(fy);
    const double s = x - fx, r = y - fy;
    return (1 - s) * (1 - r) * sample(i, j) + s * (1 - r) * sample(i + 1, j) +
           (1 - s) * r * sample(i, j + 1) + s * r * sample(i + 1, j + 1);
}

std::optional<HeightFieldHit> HeightFieldTracer::intersect(glm::dvec3 origin, glm::dvec3 direction,
                                                           double tMax) const {
    // Work in texel space, where cell (i, j) spans [i, i+1] x [j, j+1] between sample centres.
    const double x0 = origin.x * width_ - 0.5, y0 = origin.y * height_ - 0.5;
    const double dx = direction.x * width_, dy = direction.y * height_;
    const double z0 = origin.z, dz = direction.z;
    auto hitAt = [&](double t) {
        const glm::dvec2 uv = glm::dvec2(origin) + t * glm::dvec2(direction);
        return HeightFieldHit{t, uv, heightAt(uv)};
    };
    if (heightAt(glm::dvec2(origin)) >= z0) return hitAt(0.0);

    long long i = static_cast<long long>(std::floor(x0)), j = static_cast<long long>(std::floor(y0));
    const double inf = std::numeric_limits<double>::infinity();
    const int stepI = dx > 0 ? 1 : -1, stepJ = dy > 0 ? 1 : -1;
    const double tDeltaX = dx != 0 ? std::abs(1.0 / dx) : inf;
    const double tDeltaY = dy != 0 ? std::abs(1.0 / dy) : inf;
    double tNextX = dx > 0 ? (double(i + 1) - x0) / dx : dx < 0 ? (double(i) - x0) / dx : inf;
    double tNextY = dy > 0 ? (double(j + 1) - y0) / dy : dy < 0 ? (double(j) - y0) / dy : inf;

    double tEnter = 0.0;
    const long long maxCells = static_cast<long long>(std::abs(dx * tMax) + std::abs(dy * tMax)) + 4;
    for (long long n = 0; n < maxCells && tEnter <= tMax; ++n) {
        const double tExit = std::min({tNextX, tNextY, tMax});
        // f(t) = bilinear(s(t), r(t)) - z(t), quadratic in t within this cell.
        const double h00 = sample(i, j), h10 = sample(i + 1, j);
        const double h01 = sample(i, j + 1), h11 = sample(i + 1, j + 1);
        const double s0 = x0 - double(i), r0 = y0 - double(j);
        const double a = h00, b = h10 - h00, c = h01 - h00, d = h00 - h10 - h01 + h11;
        // h = a + b s + c r + d s r with s = s0 + dx t, r = r0 + dy t.
        const double qa = d * dx * dy;
        const double qb = b * dx + c * dy + d * (s0 * dy + r0 * dx) - dz;
        const double qc = a + b * s0 + c * r0 + d * s0 * r0 - z0;
        double root = inf;
        auto consider = [&](double t) {
            if (t >= tEnter - 1e-12 && t <= tExit + 1e-12) root = std::min(root, std::max(t, tEnter));
        };
        if (std::abs(qa) < 1e-14) {
            if (qb != 0) consider(-qc / qb);
        } else {
            const double disc = qb * qb - 4 * qa * qc;
            if (disc >= 0) {
                const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
                consider(q / qa);
                if (q != 0) consider(qc / q);
            }
        }
        if (root <= tMax) return hitAt(root);
        if (tExit >= tMax) break;
        tEnter = tExit;
        if (tNextX < tNextY) {
            i += stepI;
            tNextX += tDeltaX;
        } else {
            j += stepJ;
            tNextY += tDeltaY;
        }
    }
    return std::nullopt;
}

std::optional<HeightFieldHit> HeightFieldTracer::traceView(glm::dvec2 uv0, glm::dvec3 toEye,
                                                           double depthScale) const {
    if (!(toEye.z > 0) || !(depthScale > 0)) return HeightFieldHit{0.0, uv0, heightAt(uv0)};
    // Per unit of depth fraction the ray moves -toEye.xy / toEye.z * depthScale in uv and
    // drops by one in height.
    const glm::dvec3 direction(-toEye.x / toEye.z * depthScale, -toEye.y / toEye.z * depthScale, -1.0);
    return intersect({uv0.x, uv0.y, 1.0}, direction, 1.0);
}

} // namespace hfx
