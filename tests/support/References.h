#pragma once
// Plain single-threaded C++ references of the compute kernels, written from the same shared
// math headers: what the tests compare the kernels with and the benchmarks time them against.

#include "hfx/compute/DecalMap.h"
#include "hfx/compute/GasField.h"
#include "hfx/compute/PolarFilter.h"
#include "hfx/compute/WaveField.h"
#include "hfx/core/EdgeMode.h"
#include "hfx/compute/shared/GasMath.h"

#include <glm/vec3.hpp>

#include <vector>

namespace hfx::test {

/// The waves formula as written, sin(2 pi (m u + n v) + phase) evaluated directly in double:
/// the kernel takes the separable route through per-row and per-column tables.
std::vector<float> wavesReference(const WaveConfig& config, double t);

/// Sobel normals (float4 per texel) of a periodic size x size field, from SobelMath.h.
std::vector<float> sobelReference(const std::vector<float>& heights, int size, float depthScale);

/// Each stamp over its own footprint, in batch order: how one thread would stamp.
void decalsReference(const DecalConfig& config, const std::vector<float>& base, std::vector<float>& damage,
                     const std::vector<BulletHole>& stamps);

/// The light the lit model emits at heat t, 0 to 1 (shaders/shade/lit.glsl's hfx_ember, written
/// out): 2.5 t^2 (1, 0.12 + 0.6 t^2, 0.02 + 0.4 t^4), linear RGB.
inline glm::dvec3 emberReference(double t) {
    const double t2 = t * t;
    return 2.5 * t2 * glm::dvec3(1.0, 0.12 + 0.6 * t2, 0.02 + 0.4 * t2 * t2);
}

/// Level 0 and the reductions of the height-bounds pyramid as (max, min) pairs, concatenated like
/// BoundsPyramid's buffer.
std::vector<float> pyramidReference(const std::vector<float>& heights, int width, int height);

// One step of GasField, written out on the host with the same per-cell functions (without the
// dye-mass correction, a global rescale that DyeMassIsConserved checks).
struct GasReference {
    GasConfig c;
    std::vector<float> u, v, dye;
    std::vector<float> metric = gasMetricTable(c);
    std::vector<float> grid = gasMetricTable({.width = c.width, .height = c.height}); // the confinement's
    int W() const { return c.width; }
    int H() const { return c.height; }
    int walls() const { return wrapsV(c.edges) ? 0 : 1; }
    template <typename F>
    std::vector<float> map(F&& f) const {
        std::vector<float> out(size_t(W()) * H());
        for (int j = 0; j < H(); ++j)
            for (int i = 0; i < W(); ++i) out[size_t(j) * W() + i] = f(i, j);
        return out;
    }
    std::vector<float> advect(const std::vector<float>& src, float ox, float oy, float dt, bool wallRow) const {
        auto plain = [&](const std::vector<float>& s, float step) {
            return map([&](int i, int j) {
                return (walls() && wallRow && j == 0)
                           ? 0.0f
                           : hfx_gas_advect(u.data(), v.data(), metric.data(), s.data(), W(), H(), i, j, ox, oy, step,
                                            walls());
            });
        };
        if (!c.maccormack) return plain(src, dt);
        const auto forward = plain(src, dt), backward = plain(forward, -dt);
        return map([&](int i, int j) {
            return (walls() && wallRow && j == 0)
                       ? 0.0f
                       : hfx_gas_maccormack(u.data(), v.data(), metric.data(), src.data(), forward.data(),
                                            backward.data(), W(), H(), i, j, ox, oy, dt, walls());
        });
    }
    void step(float dt) {
        if (c.vorticity > 0) {
            const auto w =
                map([&](int i, int j) { return hfx_gas_curl(u.data(), v.data(), grid.data(), W(), H(), i, j); });
            for (int j = 0; j < H(); ++j)
                for (int i = 0; i < W(); ++i) {
                    float a[2], b[2];
                    hfx_gas_confinement(w.data(), W(), H(), i, j, c.vorticity, a);
                    hfx_gas_confinement(w.data(), W(), H(), hfx_gas_step(i - 1, W()), j, c.vorticity, b);
                    u[j * W() + i] += dt * 0.5f * (a[0] + b[0]);
                    if (walls() && j == 0) continue;
                    hfx_gas_confinement(w.data(), W(), H(), i, hfx_gas_step(j - 1, H()), c.vorticity, b);
                    v[j * W() + i] += dt * 0.5f * (a[1] + b[1]);
                }
        }
        if (c.sphere) {
            std::vector<float> ut(u.size()), vt(v.size()), zonal(static_cast<size_t>(H()));
            for (int j = 0; j < H(); ++j) zonal[size_t(j)] = hfx_gas_row_sum(u.data() + j * W(), W());
            for (int j = 0; j < H(); ++j)
                for (int i = 0; i < W(); ++i)
                    hfx_gas_turn(u.data(), v.data(), metric.data(), zonal.data(), W(), H(), i, j, dt, walls(),
                                 &ut[j * W() + i], &vt[j * W() + i]);
            u = ut;
            v = vt;
        }
        const auto u2 = advect(u, 0.0f, 0.5f, dt, false);
        const auto v2 = advect(v, 0.5f, 0.0f, dt, true);
        u = u2;
        v = v2;
        for (int j = 1; j < H() && walls(); ++j) { // each face row's mean v (gas.cl's remove_row_mean)
            double sum = 0;
            for (int i = 0; i < W(); ++i) sum += v[j * W() + i];
            for (int i = 0; i < W(); ++i) v[j * W() + i] -= float(sum / W());
        }
        std::vector<float> div =
            map([&](int i, int j) { return hfx_gas_divergence(u.data(), v.data(), metric.data(), W(), H(), i, j); });
        std::vector<float> p(div.size(), 0.0f);
        for (int it = 0; it < c.pressureIterations; ++it)
            p = map([&](int i, int j) {
                return hfx_gas_pressure_jacobi(p.data(), div.data(), metric.data(), W(), H(), i, j, walls());
            });
        for (int j = 0; j < H(); ++j)
            for (int i = 0; i < W(); ++i) {
                const int k = j * W() + i;
                u[k] -= (p[k] - p[j * W() + hfx_gas_step(i - 1, W())]) / metric[size_t(2 * j + 1)];
                v[k] = (walls() && j == 0) ? 0.0f : v[k] - (p[k] - p[hfx_gas_step(j - 1, H()) * W() + i]);
            }
        dye = advect(dye, 0.5f, 0.5f, dt, false);
        if (c.sphere) dye = PolarFilter::reference(dye, W(), H(), gasPolarWidths(c));
    }
};


} // namespace hfx::test
