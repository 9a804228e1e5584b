#include "hfx/compute/OceanQuery.h"
#include "hfx/compute/shared/OceanMath.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <fftw3.h>

#include <cmath>
#include <mutex>
#include <numbers>

namespace hfx {
namespace {

/// FFTW's planner is not thread-safe (its execute is): plans are made and destroyed under this.
std::mutex plannerMutex;

struct FftwFree {
    void operator()(void* p) const { fftwf_free(p); }
};
template <typename T> using FftwArray = std::unique_ptr<T[], FftwFree>;

template <typename T> FftwArray<T> fftwArray(size_t n) {
    T* p = static_cast<T*>(fftwf_malloc(n * sizeof(T)));
    if (!p)
        throw Error(str("OceanQuery: out of memory for ", n, " FFT values"));
    return FftwArray<T>(p);
}

struct PlanDeleter {
    void operator()(fftwf_plan p) const {
        std::lock_guard<std::mutex> lock(plannerMutex);
        fftwf_destroy_plan(p);
    }
};
using Plan = std::unique_ptr<std::remove_pointer_t<fftwf_plan>, PlanDeleter>;

} // namespace

/// The snapshot of the spectra and the grids of the last time asked for.
struct OceanQuery::Grids {
    struct Cascade {
        double patchMeters = 0.0;
        float lambdaPerTexel = 0.0f;
        std::vector<std::complex<float>> h0From, h0;
        std::vector<float> omega;
        FftwArray<float> fields;     ///< h, Dx, Dy on the Lagrangian grid (3 N^2)
        std::vector<float> packed; ///< the grid packed as ocean_eulerian reads it (hfx_ocean_pack)
    };
    int N = 0;
    float choppiness = 0.0f;
    float repeatSeconds = 0.0f;
    WindBlend blend;
    std::vector<Cascade> cascades;
    FftwArray<fftwf_complex> spectra; ///< the half spectra of h, Dx, Dy: 3 x N x (N/2 + 1)
    Plan plan;                        ///< c2r of those three into a cascade's fields
    bool valid = false;
    double time = 0.0;
};

OceanQuery::OceanQuery(const OceanField& ocean) : grids_(std::make_unique<Grids>()) {
    Grids& g = *grids_;
    g.N = ocean.config().size;
    const int N = g.N;
    const size_t n = size_t(N) * N, half = size_t(N / 2 + 1) * N;
    g.spectra = fftwArray<fftwf_complex>(3 * half);
    g.cascades.resize(size_t(ocean.cascadeCount()));
    for (Grids::Cascade& c : g.cascades) {
        c.fields = fftwArray<float>(3 * n);
        c.packed.assign(HFX_OCEAN_PACKED * n, 0.0f);
    }
    {
        // Three 2D complex-to-real transforms of the (N/2 + 1)-wide halves, unnormalised (a
        // field is the plain sum of its modes), as InverseRealFft does on the device. The rows are y,
        // the halved dimension x, the layout ocean_spectrum writes.
        const int dims[2] = {N, N};
        std::lock_guard<std::mutex> lock(plannerMutex);
        fftwf_plan p = fftwf_plan_many_dft_c2r(2, dims, 3, g.spectra.get(), nullptr, 1, int(half),
                                               g.cascades.front().fields.get(), nullptr, 1, int(n),
                                               FFTW_ESTIMATE);
        if (!p)
            throw Error(str("OceanQuery: FFTW could not plan the ", N, "x", N, " transforms"));
        g.plan.reset(p);
    }
    update(ocean);
}

OceanQuery::~OceanQuery() = default;
OceanQuery::OceanQuery(OceanQuery&&) noexcept = default;
OceanQuery& OceanQuery::operator=(OceanQuery&&) noexcept = default;

int OceanQuery::cascadeCount() const {
    return int(grids_->cascades.size());
}

void OceanQuery::update(const OceanField& ocean) {
    Grids& g = *grids_;
    if (ocean.config().size != g.N || ocean.cascadeCount() != cascadeCount())
        throw Error(str("OceanQuery::update: the query was made for ", cascadeCount(),
                        " cascades of ", g.N, "^2, the ocean has ", ocean.cascadeCount(), " of ",
                        ocean.config().size, "^2"));
    g.choppiness = ocean.config().choppiness;
    g.repeatSeconds = ocean.config().repeatSeconds;
    g.blend = ocean.windBlend();
    for (int i = 0; i < cascadeCount(); ++i) {
        const OceanCascade& from = ocean.cascade(i);
        Grids::Cascade& c = g.cascades[size_t(i)];
        c.patchMeters = from.patchMeters;
        c.lambdaPerTexel = g.choppiness / (from.patchMeters / float(g.N)); // as OceanField::compute
        c.h0From = from.h0From;
        c.h0 = from.h0;
        c.omega = from.omega;
    }
    g.valid = false;
}

void OceanQuery::prepare(double t) {
    Grids& g = *grids_;
    if (g.valid && g.time == t)
        return;
    const int N = g.N;
    const size_t n = size_t(N) * N, half = size_t(N / 2 + 1) * N;
    const float tp = OceanField::periodicTime(t, g.repeatSeconds);
    const float blend = float(g.blend.at(t));
    const bool displacement = g.choppiness > 0.0f;
    for (Grids::Cascade& c : g.cascades) {
        // ocean_spectrum, in the same float operations.
        const float dk = float(2.0 * std::numbers::pi / c.patchMeters);
        for (int y = 0; y < N; ++y)
            for (int x = 0; x <= N / 2; ++x) {
                const int k = y * N + x, mk = ((N - y) % N) * N + (N - x) % N;
                float are, aim, bre, bim, re, im;
                hfx_ocean_blend(c.h0From[size_t(k)].real(), c.h0From[size_t(k)].imag(),
                                c.h0[size_t(k)].real(), c.h0[size_t(k)].imag(), blend, &are, &aim);
                hfx_ocean_blend(c.h0From[size_t(mk)].real(), c.h0From[size_t(mk)].imag(),
                                c.h0[size_t(mk)].real(), c.h0[size_t(mk)].imag(), blend, &bre,
                                &bim);
                hfx_ocean_mode(are, aim, bre, bim, -c.omega[size_t(k)] * tp, &re, &im);
                const size_t o = size_t(y) * (N / 2 + 1) + size_t(x);
                g.spectra[o][0] = re;
                g.spectra[o][1] = im;
                const float kx = dk * float(x), ky = dk * float(y < N / 2 ? y : y - N);
                const float len = std::sqrt(kx * kx + ky * ky);
                const float ux = len > 0.0f ? kx / len : 0.0f, uy = len > 0.0f ? ky / len : 0.0f;
                g.spectra[half + o][0] = -im * ux;
                g.spectra[half + o][1] = re * ux;
                g.spectra[2 * half + o][0] = -im * uy;
                g.spectra[2 * half + o][1] = re * uy;
            }
        fftwf_execute_dft_c2r(g.plan.get(), g.spectra.get(), c.fields.get());
        float* f = c.fields.get();
        if (!displacement)
            std::fill(f + n, f + 3 * n, 0.0f);
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < N; ++i)
                hfx_ocean_pack(f, N, c.lambdaPerTexel, i, j, 0.0f, 0.0f, c.packed.data());
    }
    g.valid = true;
    g.time = t;
}

float OceanQuery::cascadeHeight(int cascade, glm::vec2 point) const {
    const Grids& g = *grids_;
    const Grids::Cascade& c = g.cascades[size_t(cascade)];
    const int iterations = g.choppiness > 0.0f ? OceanField::eulerianIterations : 0;
    // The Eulerian height at a texel, as ocean_eulerian computes it.
    auto eulerian = [&](int i, int j) {
        const HfxOceanCell cell = hfx_ocean_lagrangian_texel(c.packed.data(), g.N, c.lambdaPerTexel,
                                                             iterations, i, j);
        return hfx_ocean_lerp(c.packed.data(), cell, HFX_OCEAN_H);
    };
    // Into the patch in double, then texels, so points kilometres out keep their precision;
    // between texels bilinear, as the renderer filters OceanCascade::meters.
    auto texel = [&](double metres) {
        const double r = metres - c.patchMeters * std::floor(metres / c.patchMeters);
        return r / c.patchMeters * g.N;
    };
    const double x = texel(point.x), y = texel(point.y);
    const int i = int(std::floor(x)), j = int(std::floor(y)), m = g.N - 1;
    const float ax = float(x - i), ay = float(y - j);
    const float a = eulerian(i & m, j & m), b = eulerian((i + 1) & m, j & m);
    const float d = eulerian(i & m, (j + 1) & m), e = eulerian((i + 1) & m, (j + 1) & m);
    const float top = a + ax * (b - a), bottom = d + ax * (e - d);
    return top + ay * (bottom - top);
}

void OceanQuery::check(std::span<const glm::vec2> points, double t) const {
    if (!std::isfinite(t))
        throw Error(str("OceanQuery: time must be finite, got ", t));
    for (size_t i = 0; i < points.size(); ++i)
        if (!isFinite(points[i])) throw Error(str("OceanQuery: point ", i, " is not finite ", text(points[i])));
}

void OceanQuery::heights(std::span<const glm::vec2> points, double t, std::span<float> out) {
    if (out.size() != points.size())
        throw Error(
            str("OceanQuery::heights: ", out.size(), " outputs for ", points.size(), " points"));
    check(points, t);
    prepare(t);
    for (size_t i = 0; i < points.size(); ++i) {
        float sum = 0.0f;
        for (int c = 0; c < cascadeCount(); ++c)
            sum += cascadeHeight(c, points[i]);
        out[i] = sum;
    }
}

std::vector<float> OceanQuery::heights(std::span<const glm::vec2> points, double t) {
    std::vector<float> out(points.size());
    heights(points, t, out);
    return out;
}

std::vector<float> OceanQuery::cascadeHeights(int cascade, std::span<const glm::vec2> points,
                                              double t) {
    if (cascade < 0 || cascade >= cascadeCount())
        throw Error(str("OceanQuery::cascadeHeights: cascade ", cascade, " of ", cascadeCount()));
    check(points, t);
    prepare(t);
    std::vector<float> out(points.size());
    for (size_t i = 0; i < points.size(); ++i)
        out[i] = cascadeHeight(cascade, points[i]);
    return out;
}

} // namespace hfx
