#include "hfx/compute/OceanField.h"
#include "hfx/compute/InverseRealFft.h"
#include "hfx/compute/shared/OceanMath.h"

#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>

namespace hfx {
namespace {

constexpr double kPi = std::numbers::pi;

} // namespace

void FoamConfig::validate() const {
    if (!(threshold <= 2.0f)) throw Error(str("FoamConfig.threshold must be at most 2 (< 0: automatic), got ", threshold));
    if (!(coverage >= 0.0f && coverage <= 20.0f)) throw Error(str("FoamConfig.coverage must be in [0, 20], got ", coverage));
    if (!(injection >= 0.0f) || !std::isfinite(injection))
        throw Error(str("FoamConfig.injection must be >= 0, got ", injection));
    if (!(halfLife > 0.0f) || !std::isfinite(halfLife))
        throw Error(str("FoamConfig.halfLife must be positive seconds, got ", halfLife));
    if (!(youngHalfLife > 0.0f && std::isfinite(youngHalfLife)))
        throw Error(str("FoamConfig.youngHalfLife must be positive seconds, got ", youngHalfLife));
    if (!(drift >= 0.0f && drift <= 1.0f)) throw Error(str("FoamConfig.drift must be in [0, 1], got ", drift));
    if (!(shortestWhitecap >= 0.0f) || !std::isfinite(shortestWhitecap))
        throw Error(str("FoamConfig.shortestWhitecap must be >= 0 metres, got ", shortestWhitecap));
}

void OceanConfig::validate() const {
    if (size < 16 || size > 1024 || (size & (size - 1)) != 0)
        throw Error(str("OceanConfig.size must be a power of two in [16, 1024], got ", size));
    if (cascades < 1 || cascades > 4) throw Error(str("OceanConfig.cascades must be in [1, 4], got ", cascades));
    if (!(patchMeters >= 0.0f) || !std::isfinite(patchMeters))
        throw Error(str("OceanConfig.patchMeters must be >= 0 (0: from the sea state), got ", patchMeters));
    if (!(cascadeRatio > 2.0f && cascadeRatio <= 8.0f))
        throw Error(str("OceanConfig.cascadeRatio must be in (2, 8], got ", cascadeRatio));
    // The next cascade's band starts where this one keeps 8 texels per wave, pi N / (4 L); it
    // needs 6 of its own lattice steps (2 pi / L') there, so L / L' <= N / 48.
    if (cascades > 1 && cascadeRatio > float(size) / 48.0f)
        throw Error(str("OceanConfig.cascadeRatio ", cascadeRatio, " is too large for ", size,
                        "-texel cascades (at most size / 48 = ", float(size) / 48.0f,
                        "): the next cascade would start its band within 6 lattice steps of its origin"));
    sea.validate();
    if (!(choppiness >= 0.0f && choppiness <= 4.0f))
        throw Error(str("OceanConfig.choppiness must be in [0, 4], got ", choppiness));
    if (!(repeatSeconds >= 1.0f) || !std::isfinite(repeatSeconds))
        throw Error(str("OceanConfig.repeatSeconds must be >= 1, got ", repeatSeconds));
    foam.validate();
}

std::vector<float> OceanConfig::cascadeLengths() const {
    float largest = patchMeters;
    if (largest == 0.0f) {
        const double wp = sea.wind.peakFrequency();
        const double peakWavelength = 2.0 * kPi * kGravity / (wp * wp); // deep water
        largest = float(std::max(200.0, 8.0 * peakWavelength));
    }
    std::vector<float> lengths;
    for (int i = 0; i < cascades; ++i) lengths.push_back(largest / std::pow(cascadeRatio, float(i)));
    return lengths;
}

float OceanField::quantisedOmega(double k, double depth, double repeatSeconds) {
    const double w0 = 2.0 * kPi / repeatSeconds;
    return float(std::floor(dispersion(k, depth) / w0) * w0);
}

void OceanField::waveVector(int x, int y, int n, double patchMeters, double& kx, double& ky) {
    const double dk = 2.0 * kPi / patchMeters;
    kx = dk * (x < n / 2 ? x : x - n);
    ky = dk * (y < n / 2 ? y : y - n);
}

namespace {
/// The bands: cascade i keeps k in [k_i, k_i+1), where k_i+1 = pi N / (4 L_i) keeps 8 of its
/// texels per wave; the first starts at 0.
void bandOf(const OceanConfig& c, const std::vector<float>& lengths, int i, float& kMin, float& kMax) {
    kMin = i == 0 ? 0.0f : float(kPi * c.size / (4.0 * lengths[size_t(i - 1)]));
    kMax = float(kPi * c.size / (4.0 * lengths[size_t(i)]));
}
} // namespace

std::vector<std::complex<float>> OceanField::spectrumAmplitudes(const OceanConfig& config, int cascade) {
    config.validate();
    const std::vector<float> lengths = config.cascadeLengths();
    if (cascade < 0 || cascade >= config.cascades)
        throw Error(str("OceanField::spectrumAmplitudes: cascade ", cascade, " of ", config.cascades));
    float kMin, kMax;
    bandOf(config, lengths, cascade, kMin, kMax);
    const int N = config.size;
    const double L = lengths[size_t(cascade)], dk = 2.0 * kPi / L;
    std::vector<std::complex<float>> h0(size_t(N) * N);
    // One random phase per wave vector, from a stream per cascade: the same seed draws the same
    // sea on every machine. The magnitude is the spectrum's own (no random amplitude), so the
    // sea's variance is the spectrum's, exactly: |h0|^2 = Psi dk^2 / 2 and the pair k, -k give
    // E|h(k, t)|^2 = Psi dk^2.
    SplitMix64 random(config.seed * 0x9E3779B97F4A7C15ull + std::uint64_t(cascade) + 1);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            double kx, ky;
            waveVector(x, y, N, L, kx, ky);
            const double phase = 2.0 * kPi * random.next();
            const double k = std::hypot(kx, ky);
            if (!(k >= kMin && k < kMax)) continue;
            const double magnitude = std::sqrt(config.sea.density(kx, ky) * dk * dk / 2.0);
            h0[size_t(y) * N + x] = {float(magnitude * std::cos(phase)), float(magnitude * std::sin(phase))};
        }
    return h0;
}

float OceanField::sigmaMeters() const {
    double variance = 0.0;
    for (const OceanCascade& c : cascades_) variance += double(c.sigma) * c.sigma;
    return float(std::sqrt(variance));
}

float OceanField::periodicTime(double seconds, float repeatSeconds) {
    const double r = std::fmod(seconds, double(repeatSeconds));
    return float(r < 0.0 ? r + double(repeatSeconds) : r);
}

double WindBlend::at(double time) const {
    if (seconds <= 0.0) return 1.0;
    const double s = std::clamp((time - start) / seconds, 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
}

void OceanField::setWind(float speed, float direction, double blendSeconds) {
    if (!(blendSeconds >= 0.0) || !std::isfinite(blendSeconds))
        throw Error(str("OceanField::setWind: blendSeconds must be >= 0 and finite, got ", blendSeconds));
    OceanConfig next = config_;
    next.sea.wind.windSpeed = speed;
    next.sea.wind.direction = direction;
    next.patchMeters = config_.cascadeLengths().front(); // the cascades keep their lengths
    std::vector<std::vector<std::complex<float>>> h0;
    for (int i = 0; i < next.cascades; ++i) h0.push_back(spectrumAmplitudes(next, i)); // validates first
    config_ = next;
    const double s = blend_.at(time_);
    for (size_t i = 0; i < cascades_.size(); ++i) {
        OceanCascade& c = cascades_[i];
        if (blendSeconds > 0.0) {
            // From the sea as it is now, mid-blend included.
            for (size_t k = 0; k < c.h0.size(); ++k) {
                float re, im;
                hfx_ocean_blend(c.h0From[k].real(), c.h0From[k].imag(), c.h0[k].real(), c.h0[k].imag(), float(s), &re, &im);
                c.h0From[k] = {re, im};
            }
        } else {
            c.h0From = h0[i];
        }
        c.h0 = std::move(h0[i]);
        uploadAmplitudes(c);
    }
    blend_ = {.start = time_, .seconds = blendSeconds};
    compute(0.0);
    if (blendSeconds > 0.0) calibrateAfterBlend_ = true; // J's statistics are the new sea's once it is there
    else calibrateFoam();
}

void OceanField::setAmplitudes(int cascade, const std::vector<std::complex<float>>& h0) {
    if (cascade < 0 || cascade >= cascadeCount())
        throw Error(str("OceanField::setAmplitudes: cascade ", cascade, " of ", cascadeCount()));
    OceanCascade& c = cascades_[size_t(cascade)];
    if (h0.size() != c.h0.size())
        throw Error(str("OceanField::setAmplitudes: ", h0.size(), " amplitudes for ", c.h0.size(), " wave vectors"));
    for (const auto& a : h0)
        if (!std::isfinite(a.real()) || !std::isfinite(a.imag()))
            throw Error("OceanField::setAmplitudes: amplitudes must be finite");
    c.h0 = h0;
    c.h0From = h0;
    uploadAmplitudes(c);
    compute(0.0);
    calibrateFoam();
}

void OceanField::makeCascade(OceanCascade& c, float patchMeters, float kMin, float kMax) {
    const int N = config_.size;
    const size_t n = size_t(N) * N;
    c.patchMeters = patchMeters;
    c.kMin = kMin;
    c.kMax = kMax;
    c.omega.resize(n);
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            double kx, ky;
            waveVector(x, y, N, patchMeters, kx, ky);
            c.omega[size_t(y) * N + x] =
                quantisedOmega(std::hypot(kx, ky), config_.sea.depthMeters, config_.repeatSeconds);
        }
    clGuard("creating an ocean cascade", [&] {
        const cl::Context& ctx = cl_.context();
        c.h0Device = cl::Buffer(ctx, CL_MEM_READ_ONLY, n * sizeof(cl_float2));
        c.h0FromDevice = cl::Buffer(ctx, CL_MEM_READ_ONLY, n * sizeof(cl_float2));
        c.omegaDevice = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(float), c.omega.data());
        c.lagrangian = cl::Buffer(ctx, CL_MEM_READ_WRITE, 3 * n * sizeof(float));
        c.jacobian = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
        c.packed = cl::Buffer(ctx, CL_MEM_READ_WRITE, HFX_OCEAN_PACKED * n * sizeof(float));
        for (cl::Buffer* pair : {c.foam, c.young})
            for (int i = 0; i < 2; ++i) {
                pair[i] = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
                cl_.queue().enqueueFillBuffer(pair[i], 0.0f, 0, n * sizeof(float));
            }
        c.height = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
        c.meters = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
        c.foamColor = cl::Buffer(ctx, CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, n * sizeof(cl_uchar4));
    });
}

OceanField::OceanField(ClContext& cl, const OceanConfig& config)
    : cl_(cl), config_((config.validate(), config)) {
    const int N = config.size;
    const std::vector<float> lengths = config.cascadeLengths();
    config_.patchMeters = lengths.front();
    cascades_.resize(size_t(config.cascades));
    for (int i = 0; i < config.cascades; ++i) {
        float kMin, kMax;
        bandOf(config_, lengths, i, kMin, kMax);
        makeCascade(cascades_[size_t(i)], lengths[size_t(i)], kMin, kMax);
        cascades_[size_t(i)].h0 = spectrumAmplitudes(config_, i);
        cascades_[size_t(i)].h0From = cascades_[size_t(i)].h0;
    }
    const int fields = config.choppiness > 0.0f ? 3 : 1;
    clGuard("creating the ocean", [&] {
        spectrum_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, size_t(fields) * size_t(N / 2 + 1) * N * sizeof(cl_float2));
        spectrumKernel_ = cl.kernel("ocean.cl", "ocean_spectrum");
        lagrangianKernel_ = cl.kernel("ocean.cl", "ocean_lagrangian");
        eulerianKernel_ = cl.kernel("ocean.cl", "ocean_eulerian");
    });
    // Out-of-place 2D inverse transforms from the Hermitian half spectra (kx index 0..N/2, rows
    // of N/2 + 1) to real fields, without the 1/N^2 scale (a field is the plain sum of its
    // modes): h, Dx and Dy in one batch. Planned now, so no frame pays for compiling it.
    fft_ = std::make_unique<InverseRealFft>(cl, N, fields);
    for (OceanCascade& c : cascades_) uploadAmplitudes(c);
    compute(0.0);
    calibrateFoam();
}

OceanField::~OceanField() = default;

double OceanField::whitecapCoverage(double windSpeed) {
    return std::min(1.0, 3.84e-6 * std::pow(std::max(windSpeed, 0.0), 3.41));
}

void OceanField::calibrateFoam() {
    const FoamConfig& f = config_.foam;
    double total = 0.0;
    for (const OceanCascade& c : cascades_) total += double(c.sigmaJWhitecaps) * c.sigmaJWhitecaps;
    const double coverage = whitecapCoverage(config_.sea.wind.windSpeed) * f.coverage;
    const size_t n = size_t(config_.size) * config_.size;
    std::vector<float> J(n);
    for (OceanCascade& c : cascades_) {
        if (f.threshold >= 0.0f) {
            c.foamThreshold = f.threshold;
            c.foamGain = f.injection;
            continue;
        }
        // This cascade's share of the coverage, by its share of the J variance of the waves that
        // whiten as they break, as the quantile of its J now: J's lower tail is thinner than a
        // Gaussian's (its quadratic terms), so the realised field sets the threshold, not
        // sigma_J alone.
        const double share =
            total > 0.0 ? coverage * double(c.sigmaJWhitecaps) * c.sigmaJWhitecaps / total : 0.0;
        if (share <= 0.0) {
            c.foamThreshold = -1.0f;
            c.foamGain = 0.0f;
            continue;
        }
        clGuard("calibrating the foam", [&] {
            cl_.queue().enqueueReadBuffer(c.jacobian, CL_TRUE, 0, n * sizeof(float), J.data());
        });
        const size_t rank = std::min(n - 1, size_t(share * double(n)));
        std::nth_element(J.begin(), J.begin() + std::ptrdiff_t(rank), J.end());
        c.foamThreshold = J[rank];
        c.foamGain = f.injection / std::max(c.sigmaJ, 1e-3f);
    }
}

void OceanField::setBlendedSigma(OceanCascade& c, double s) {
    // hfx_ocean_blend moves each mode's energy linearly, and so the variance.
    const double variance = (1.0 - s) * c.varianceFrom + s * c.varianceTo;
    c.sigma = float(std::sqrt(std::max(variance, 0.0)));
    c.scale = c.sigma > 0.0f ? 1.0f / (8.0f * c.sigma) : 1.0f;
}

void OceanField::uploadAmplitudes(OceanCascade& c) {
    // The expected variances: E|h(k, t)|^2 = |h0(k)|^2 + |h0(-k)|^2 summed over k, and J - 1,
    // about -lambda div D = lambda |k| h, has |k|^2 of each mode's.
    const int N = config_.size;
    double jVariance = 0.0, whitecapVariance = 0.0;
    const double kWhitecap = config_.foam.shortestWhitecap > 0.0f
                                 ? 2.0 * std::numbers::pi / double(config_.foam.shortestWhitecap)
                                 : std::numeric_limits<double>::infinity();
    c.varianceFrom = c.varianceTo = 0.0;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            double kx, ky;
            waveVector(x, y, N, c.patchMeters, kx, ky);
            const size_t k = size_t(y) * N + x;
            const double e = 2.0 * std::norm(c.h0[k]);
            c.varianceTo += e;
            c.varianceFrom += 2.0 * std::norm(c.h0From[k]);
            const double k2 = kx * kx + ky * ky;
            jVariance += e * k2;
            if (k2 <= kWhitecap * kWhitecap) whitecapVariance += e * k2;
        }
    c.sigmaJ = float(config_.choppiness * std::sqrt(jVariance));
    c.sigmaJWhitecaps = float(config_.choppiness * std::sqrt(whitecapVariance));
    setBlendedSigma(c, blend_.at(time_));
    clGuard("uploading the ocean spectrum", [&] {
        cl_.queue().enqueueWriteBuffer(c.h0Device, CL_TRUE, 0, c.h0.size() * sizeof(cl_float2), c.h0.data());
        cl_.queue().enqueueWriteBuffer(c.h0FromDevice, CL_TRUE, 0, c.h0From.size() * sizeof(cl_float2), c.h0From.data());
    });
}

void OceanField::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("OceanField::step: dt must be positive and finite, got ", dt));
    time_ += dt;
    compute(dt);
}

void OceanField::setTime(double seconds) {
    if (!std::isfinite(seconds)) throw Error(str("OceanField::setTime: time must be finite, got ", seconds));
    time_ = seconds;
    clGuard("clearing the foam", [&] {
        for (OceanCascade& c : cascades_)
            for (cl::Buffer* pair : {c.foam, c.young})
                for (int i = 0; i < 2; ++i)
                    cl_.queue().enqueueFillBuffer(pair[i], 0.0f, 0, pair[i].getInfo<CL_MEM_SIZE>());
    });
    compute(0.0);
}

void OceanField::settleFoam(double seconds, double dt) {
    if (!(seconds >= 0.0 && seconds <= 600.0))
        throw Error(str("OceanField::settleFoam: seconds must be in [0, 600], got ", seconds));
    if (!(dt > 0.0 && dt <= 1.0)) throw Error(str("OceanField::settleFoam: dt must be in (0, 1], got ", dt));
    const double end = time_;
    const int steps = int(std::ceil(seconds / dt));
    setTime(end - seconds);
    for (int i = 1; i <= steps; ++i) {
        const double next = end - seconds + seconds * i / steps; // ends on `end` itself
        const double step = next - time_;
        time_ = next;
        compute(step, false); // the foam's history: the heights only at the end
    }
    time_ = end;
    compute(0.0); // the fields at exactly `end` (the foam stays)
}

void OceanField::compute(double dt, bool resample) {
    const int N = config_.size;
    const float t = periodicTime(time_, config_.repeatSeconds);
    const int displacement = config_.choppiness > 0.0f ? 1 : 0;
    const double blend = blend_.at(time_);
    for (OceanCascade& c : cascades_) setBlendedSigma(c, blend);
    const FoamConfig& foam = config_.foam;
    const float decay = float(std::exp2(-dt / foam.halfLife));
    const float youngDecay = float(std::exp2(-dt / std::min(foam.youngHalfLife, foam.halfLife)));

    // dt = 0 (set-up, a jump, a new spectrum) steps no foam: it stays in the buffer it is in.
    const int back = foamFront_, front = dt > 0.0 ? 1 - foamFront_ : foamFront_;
    clGuard("OceanField::step", [&] {
        for (OceanCascade& c : cascades_) {
            const float texel = c.patchMeters / float(N);
            const float lambdaPerTexel = config_.choppiness / texel;
            spectrumKernel_.setArg(0, c.h0FromDevice);
            spectrumKernel_.setArg(1, c.h0Device);
            spectrumKernel_.setArg(2, float(blend));
            spectrumKernel_.setArg(3, c.omegaDevice);
            spectrumKernel_.setArg(4, spectrum_);
            spectrumKernel_.setArg(5, N);
            spectrumKernel_.setArg(6, t);
            spectrumKernel_.setArg(7, float(2.0 * kPi / c.patchMeters));
            spectrumKernel_.setArg(8, displacement);
            cl_.enqueue(spectrumKernel_, cl::NDRange(N / 2 + 1, N));
            fft_->enqueue(spectrum_, c.lagrangian);
            if (!displacement) {
                // No choppiness: D = 0, so the Lagrangian and Eulerian grids agree and J = 1.
                cl_.queue().enqueueFillBuffer(c.lagrangian, 0.0f, size_t(N) * N * sizeof(float),
                                              2 * size_t(N) * N * sizeof(float));
            }
            // Downwind drift, in texels per step.
            const float drift = foam.drift * config_.sea.wind.windSpeed * float(dt) / texel;
            int a = 0;
            lagrangianKernel_.setArg(a++, c.lagrangian);
            lagrangianKernel_.setArg(a++, c.foam[back]);
            lagrangianKernel_.setArg(a++, c.foam[front]);
            lagrangianKernel_.setArg(a++, c.young[back]);
            lagrangianKernel_.setArg(a++, c.young[front]);
            lagrangianKernel_.setArg(a++, c.jacobian);
            lagrangianKernel_.setArg(a++, c.packed);
            lagrangianKernel_.setArg(a++, N);
            lagrangianKernel_.setArg(a++, lambdaPerTexel);
            lagrangianKernel_.setArg(a++, decay);
            lagrangianKernel_.setArg(a++, youngDecay);
            lagrangianKernel_.setArg(a++, float(c.foamGain * dt));
            lagrangianKernel_.setArg(a++, c.foamThreshold);
            lagrangianKernel_.setArg(a++, drift * std::cos(config_.sea.wind.direction));
            lagrangianKernel_.setArg(a++, drift * std::sin(config_.sea.wind.direction));
            cl_.enqueue(lagrangianKernel_, cl::NDRange(N, N));
            if (!resample) continue;
            a = 0;
            eulerianKernel_.setArg(a++, c.packed);
            eulerianKernel_.setArg(a++, c.height);
            eulerianKernel_.setArg(a++, c.meters);
            eulerianKernel_.setArg(a++, c.foamColor);
            eulerianKernel_.setArg(a++, N);
            eulerianKernel_.setArg(a++, lambdaPerTexel);
            eulerianKernel_.setArg(a++, c.scale);
            eulerianKernel_.setArg(a++, displacement ? eulerianIterations : 0);
            cl_.enqueue(eulerianKernel_, cl::NDRange(N, N));
        }
    });
    foamFront_ = front;
    if (calibrateAfterBlend_ && blend >= 1.0) {
        calibrateAfterBlend_ = false;
        calibrateFoam();
    }
}

} // namespace hfx
