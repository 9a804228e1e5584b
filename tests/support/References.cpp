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

} // namespace hfx::test
