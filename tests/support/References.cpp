#include "support/References.h"

#include "hfx/compute/shared/DecalMath.h"
#include "hfx/compute/shared/SobelMath.h"
#include "hfx/compute/shared/WavesMath.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hfx::test {

std::vector<float> wavesReference(const WaveConfig& config, double t) {
    const auto waves = WaveField::makeWaves(config);
    const float inverse = WaveField::inverseTotalAmplitude(waves);
    const int N = config.size;
    std::vector<float> h(size_t(N) * N);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            const double u = (x + 0.5) / N, v = (y + 0.5) / N;
            double sum = 0;
            for (const Wave& w : waves) {
                const double s = std::sin(2 * std::numbers::pi * (w.m * u + w.n * v) + WaveField::phaseAt(w, t));
                sum += w.amplitude * hfx_wave_shape(float(s), config.steepness);
            }
            h[size_t(y) * N + x] = hfx_wave_height(float(sum), inverse);
        }
    return h;
}

std::vector<float> sobelReference(const std::vector<float>& heights, int size, float depthScale) {
    std::vector<float> out(heights.size() * 4);
    auto at = [&](int x, int y) { return heights[size_t((y + size) % size) * size + size_t((x + size) % size)]; };
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float dx = hfx_sobel_dx(at(x - 1, y - 1), at(x + 1, y - 1), at(x - 1, y), at(x + 1, y),
                                          at(x - 1, y + 1), at(x + 1, y + 1));
            const float dy = hfx_sobel_dy(at(x - 1, y - 1), at(x, y - 1), at(x + 1, y - 1), at(x - 1, y + 1),
                                          at(x, y + 1), at(x + 1, y + 1));
            float* o = &out[(size_t(y) * size + x) * 4];
            hfx_normal_from_slopes(dx, dy, depthScale * size, depthScale * size, o);
            o[3] = at(x, y);
        }
    return out;
}

void decalsReference(const DecalConfig& c, const std::vector<float>& base, std::vector<float>& damage,
                     const std::vector<BulletHole>& stamps) {
    const int W = c.width, H = c.height;
    for (const BulletHole& s : stamps) {
        const double reach = s.radius * (1.0 + s.rimWidth) * W + 1.0;
        const int x0 = int(std::floor(s.u * W - reach)), x1 = int(std::floor(s.u * W + reach));
        const int y0 = int(std::floor(s.v * H - reach)), y1 = int(std::floor(s.v * H + reach));
        for (int ty = y0; ty <= std::min(y1, y0 + H - 1); ++ty)
            for (int tx = x0; tx <= std::min(x1, x0 + W - 1); ++tx) {
                if ((!wrapsU(c.edges) && (tx < 0 || tx >= W)) || (!wrapsV(c.edges) && (ty < 0 || ty >= H))) continue;
                const int x = ((tx % W) + W) % W, y = ((ty % H) + H) % H;
                float dx = (x + 0.5f) - s.u * W, dy = (y + 0.5f) - s.v * H;
                if (wrapsU(c.edges)) dx -= W * std::rint(dx / W);
                if (wrapsV(c.edges)) dy -= H * std::rint(dy / H);
                const float r = std::sqrt(dx * dx + dy * dy) / (s.radius * W);
                float& d = damage[size_t(y) * W + x];
                d = hfx_apply_damage(d, hfx_crater_profile(r, s.depth, s.rimHeight, s.rimWidth), base[size_t(y) * W + x]);
            }
    }
}

std::vector<float> pyramidReference(const std::vector<float>& heights, int width, int height) {
    // (max, min) pairs, level after level.
    std::vector<float> out(2 * size_t(width) * height);
    auto at = [&](int x, int y) { return heights[size_t(y % height) * width + size_t(x % width)]; };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const auto corners = {at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1)};
            out[2 * (size_t(y) * width + x)] = std::max(corners);
            out[2 * (size_t(y) * width + x) + 1] = std::min(corners);
        }
    size_t offset = 0;
    for (int w = width, h = height; w > 1 || h > 1;) {
        const int cw = (w + 1) / 2, ch = (h + 1) / 2;
        const size_t next = offset + size_t(w) * h;
        out.resize(2 * (next + size_t(cw) * ch));
        for (int y = 0; y < ch; ++y)
            for (int x = 0; x < cw; ++x) {
                const int xa = 2 * x, ya = 2 * y, xb = std::min(xa + 1, w - 1), yb = std::min(ya + 1, h - 1);
                const size_t finer[] = {offset + size_t(ya) * w + xa, offset + size_t(ya) * w + xb,
                                        offset + size_t(yb) * w + xa, offset + size_t(yb) * w + xb};
                float hi = out[2 * finer[0]], lo = out[2 * finer[0] + 1];
                for (size_t f : finer) {
                    hi = std::max(hi, out[2 * f]);
                    lo = std::min(lo, out[2 * f + 1]);
                }
                out[2 * (next + size_t(y) * cw + x)] = hi;
                out[2 * (next + size_t(y) * cw + x) + 1] = lo;
            }
        offset = next;
        w = cw;
        h = ch;
    }
    return out;
}

std::vector<double> clearanceReference(const std::vector<float>& h, int n, EdgeMode edges, const ClearanceLight& light) {
    const bool wrapU = wrapsU(edges), wrapV = wrapsV(edges);
    auto index = [&](int i, bool wrap) { return wrap ? (i & (n - 1)) : std::clamp(i, 0, n - 1); };
    auto H = [&](int x, int y) { return double(h[size_t(index(y, wrapV)) * n + index(x, wrapU)]); };
    // A cell past an edge that clamps is the edge's cell (samples n - 2..n - 1 and 0..1 are the
    // pyramid's last and first cells; the last one's far corner clamps to itself).
    auto corners = [&](int x, int y) {
        const int cx = index(x, wrapU), cy = index(y, wrapV);
        const int nx = wrapU ? cx + 1 : std::min(cx + 1, n - 1), ny = wrapV ? cy + 1 : std::min(cy + 1, n - 1);
        return glm::dvec4(H(cx, cy), H(nx, cy), H(cx, ny), H(nx, ny));
    };
    auto cellMax = [&](int x, int y) { const glm::dvec4 c = corners(x, y); return std::max(std::max(c.x, c.y), std::max(c.z, c.w)); };
    auto cellMin = [&](int x, int y) { const glm::dvec4 c = corners(x, y); return std::min(std::min(c.x, c.y), std::min(c.z, c.w)); };
    double fieldMax = 0.0;
    for (float v : h) fieldMax = std::max(fieldMax, double(v));
    const glm::dvec2 g = glm::dvec2(light.uvPerClimb) * double(n);
    const double slack = double(light.slack) * n, pen = light.penumbra, reach = 1e-3;
    const double step = 1.0 / std::max(std::max(std::abs(g.x), std::abs(g.y)), 1e-3);
    std::vector<double> out(size_t(n) * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double lo = cellMin(i, j);
            double clear = 0.0;
            auto box = [&](double d0, double d1, int& x0, int& x1, int& y0, int& y1) {
                x0 = int(std::floor(i + std::min(g.x * d0, g.x * d1) - slack * d1 - reach));
                x1 = int(std::floor(i + 1 + std::max(g.x * d0, g.x * d1) + slack * d1 + reach));
                y0 = int(std::floor(j + std::min(g.y * d0, g.y * d1) - slack * d1 - reach));
                y1 = int(std::floor(j + 1 + std::max(g.y * d0, g.y * d1) + slack * d1 + reach));
            };
            int x0, x1, y0, y1;
            box(0.0, step, x0, x1, y0, y1);
            double rise = -1.0;
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x)
                    for (int cy = 0; cy <= 1; ++cy)
                        for (int cx = 0; cx <= 1; ++cx) {
                            // The patch's gradient at its corner (cx, cy).
                            const double dx = H(x + 1, y + cy) - H(x, y + cy), dy = H(x + cx, y + 1) - H(x + cx, y);
                            rise = std::max(rise, dx * g.x + dy * g.y + slack * (std::abs(dx) + std::abs(dy)));
                        }
            if (rise > 1.0 - 1e-4) clear = step;
            const double end = std::min((fieldMax - lo) / (1.0 - pen), 1.0 - lo);
            for (int k = 1; k * step < end; ++k) {
                box(k * step, (k + 1) * step, x0, x1, y0, y1);
                double top = -1e30;
                for (int y = y0; y <= y1; ++y)
                    for (int x = x0; x <= x1; ++x) top = std::max(top, cellMax(x, y));
                if (top > lo + k * step * (1.0 - pen) - 1e-5) clear = (k + 1) * step;
            }
            out[size_t(j) * n + i] = clear;
        }
    return out;
}

} // namespace hfx::test
