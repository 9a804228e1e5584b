#include "hfx/compute/OceanField.h"

#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <clFFT.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <numbers>

namespace hfx {
namespace {

constexpr double kGravity = 9.81;
constexpr double kPi = std::numbers::pi;

void checkFft(clfftStatus status, const char* what) {
    if (status != CLFFT_SUCCESS)
        throw Error(str("clFFT: ", what, " failed with status ", int(status), " (", clErrorName(status), ")"));
}

// clfftSetup / clfftTeardown are process-wide: the first ocean sets up, the last tears down.
std::mutex libraryMutex;
int libraryUsers = 0;

/// clFFT compiles its kernels at every start unless CLFFT_CACHE_PATH names a folder for their
/// binaries; unless the user set it, it points into HFX's kernel cache. clFFT reads it in clfftSetup.
void shareKernelCache(const ProgramCache& cache) {
    if (!cache.enabled() || std::getenv("CLFFT_CACHE_PATH")) return;
    const std::filesystem::path folder = cache.folder() / "clfft";
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (!ec) setenv("CLFFT_CACHE_PATH", folder.c_str(), 0);
}

void acquireLibrary(const ProgramCache& cache) {
    std::lock_guard<std::mutex> lock(libraryMutex);
    if (libraryUsers++ == 0) {
        shareKernelCache(cache);
        clfftSetupData setup;
        checkFft(clfftInitSetupData(&setup), "clfftInitSetupData");
        const clfftStatus status = clfftSetup(&setup);
        if (status != CLFFT_SUCCESS) {
            --libraryUsers;
            checkFft(status, "clfftSetup");
        }
    }
}

/// clFFT generates its kernels with AMD's `max_constant_size` attribute, which clang (PoCL's
/// compiler) warns about on every cold build ("2 warnings generated"), and offers no hook for
/// build options. PoCL reads POCL_EXTRA_BUILD_FLAGS at each build, so "-w" is set for the bake
/// alone, unless the user set the variable. HFX's own kernels are held to -Werror by
/// ClContextTest.EveryKernelBuildsWithoutWarnings.
template <typename F>
void withoutClfftWarnings(F&& bake) {
    const bool ours = std::getenv("POCL_EXTRA_BUILD_FLAGS") == nullptr;
    if (ours) setenv("POCL_EXTRA_BUILD_FLAGS", "-w", 0);
    try {
        bake();
    } catch (...) {
        if (ours) unsetenv("POCL_EXTRA_BUILD_FLAGS");
        throw;
    }
    if (ours) unsetenv("POCL_EXTRA_BUILD_FLAGS");
}

void releaseLibrary() {
    std::lock_guard<std::mutex> lock(libraryMutex);
    if (--libraryUsers == 0) clfftTeardown();
}

/// Wave-number spectral density Psi(k) (m^4): Psi dk_x dk_y is the variance of those waves.
double spectralDensity(const OceanConfig& c, double kx, double ky) {
    const double k = std::hypot(kx, ky);
    if (k == 0.0) return 0.0;
    const double wind = c.windDirection;
    const double cosTheta = (kx * std::cos(wind) + ky * std::sin(wind)) / k;
    const double smallWaves = std::exp(-std::pow(k * c.smallWaveMeters, 2.0));
    if (c.spectrum == OceanSpectrum::Phillips) {
        // Phillips' k^-4 saturation range with his constant 0.0081, cut below the longest
        // wave the wind raises (L = V^2 / g), spread as |cos|^p around the wind.
        const double L = c.windSpeed * c.windSpeed / kGravity;
        // |cos|^p normalised to integrate to 1 over the circle.
        const double spread = std::pow(std::abs(cosTheta), c.directionality) *
                              std::tgamma(c.directionality / 2 + 1) /
                              (std::sqrt(kPi) * std::tgamma(c.directionality / 2 + 0.5)) / 2.0;
        return 0.0081 / (2.0 * kPi) * std::exp(-1.0 / (k * L * k * L)) / (k * k * k * k) * spread * smallWaves;
    }
    // JONSWAP (Hasselmann et al. 1973) in frequency, with fetch-limited peak and alpha, spread
    // as (2 / pi) cos^2 around the wind, converted to wave numbers through w^2 = g k.
    const double U = c.windSpeed, F = c.fetchKm * 1000.0;
    const double omega = std::sqrt(kGravity * k);
    const double omegaPeak = 22.0 * std::cbrt(kGravity * kGravity / (U * F));
    const double alpha = 0.076 * std::pow(U * U / (F * kGravity), 0.22);
    const double sigma = omega <= omegaPeak ? 0.07 : 0.09;
    const double r = std::exp(-std::pow(omega - omegaPeak, 2.0) / (2.0 * sigma * sigma * omegaPeak * omegaPeak));
    const double S = alpha * kGravity * kGravity / std::pow(omega, 5.0) *
                     std::exp(-1.25 * std::pow(omegaPeak / omega, 4.0)) * std::pow(3.3, r);
    const double spread = cosTheta > 0 ? 2.0 / kPi * cosTheta * cosTheta : 0.0;
    const double dOmegaDk = kGravity / (2.0 * omega);
    return S * spread * dOmegaDk / k * smallWaves;
}

} // namespace

struct OceanField::Plan {
    clfftPlanHandle handle = 0;
    ~Plan() {
        if (handle) clfftDestroyPlan(&handle);
    }
};

void OceanConfig::validate() const {
    if (size < 8 || size > 4096 || (size & (size - 1)) != 0)
        throw Error(str("OceanConfig.size must be a power of two in [8, 4096], got ", size));
    if (!(patchMeters > 0.0f) || !std::isfinite(patchMeters))
        throw Error(str("OceanConfig.patchMeters must be positive, got ", patchMeters));
    if (!(windSpeed > 0.0f) || windSpeed > 100.0f)
        throw Error(str("OceanConfig.windSpeed must be in (0, 100] m/s, got ", windSpeed));
    if (!std::isfinite(windDirection))
        throw Error(str("OceanConfig.windDirection must be finite, got ", windDirection));
    if (!(fetchKm > 0.0f) || fetchKm > 10000.0f)
        throw Error(str("OceanConfig.fetchKm must be in (0, 10000], got ", fetchKm));
    if (!(directionality >= 0.0f) || directionality > 32.0f)
        throw Error(str("OceanConfig.directionality must be in [0, 32], got ", directionality));
    if (!(smallWaveMeters >= 0.0f) || !std::isfinite(smallWaveMeters))
        throw Error(str("OceanConfig.smallWaveMeters must be >= 0, got ", smallWaveMeters));
    if (!(repeatSeconds >= 1.0f) || !std::isfinite(repeatSeconds))
        throw Error(str("OceanConfig.repeatSeconds must be >= 1, got ", repeatSeconds));
}

float OceanField::quantisedOmega(double k, double repeatSeconds) {
    const double w0 = 2.0 * kPi / repeatSeconds;
    return float(std::floor(std::sqrt(kGravity * k) / w0) * w0);
}

std::vector<std::complex<float>> OceanField::spectrumAmplitudes(const OceanConfig& config) {
    config.validate();
    const int N = config.size;
    std::vector<std::complex<float>> h0(size_t(N) * N);
    SplitMix64 random(config.seed);
    const double dk = 2.0 * kPi / config.patchMeters;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            const int kxIndex = x < N / 2 ? x : x - N, kyIndex = y < N / 2 ? y : y - N;
            const double kx = dk * kxIndex, ky = dk * kyIndex;
            // Box-Muller: two unit Gaussians, one complex amplitude of variance Psi dk^2 / 2 per part.
            const double r = std::sqrt(-2.0 * std::log(1.0 - random.next())), a = 2.0 * kPi * random.next();
            const double amplitude = std::sqrt(spectralDensity(config, kx, ky) * dk * dk / 2.0);
            h0[size_t(y) * N + x] = {float(amplitude * r * std::cos(a)), float(amplitude * r * std::sin(a))};
        }
    return h0;
}

void OceanField::setWind(float speed, float direction) {
    OceanConfig next = config_;
    next.windSpeed = speed;
    next.windDirection = direction;
    auto h0 = spectrumAmplitudes(next); // validates; throws before anything changes
    config_ = next;
    h0_ = std::move(h0);
    uploadAmplitudes();
    compute();
}

OceanField::OceanField(ClContext& cl, const OceanConfig& config)
    : cl_(cl), config_((config.validate(), config)), plan_(std::make_unique<Plan>()) {
    const int N = config.size;
    const size_t n = size_t(N) * N;
    h0_ = spectrumAmplitudes(config);
    omega_.resize(n);
    const double dk = 2.0 * kPi / config.patchMeters;
    for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x) {
            const int kxIndex = x < N / 2 ? x : x - N, kyIndex = y < N / 2 ? y : y - N;
            omega_[size_t(y) * N + x] = quantisedOmega(std::hypot(dk * kxIndex, dk * kyIndex), config.repeatSeconds);
        }
    clGuard("creating the ocean", [&] {
        h0Buffer_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY, n * sizeof(cl_float2));
        omegaBuffer_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY, n * sizeof(float));
        spectrum_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, size_t(N / 2 + 1) * N * sizeof(cl_float2));
        field_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, n * sizeof(float));
        height_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, n * sizeof(float));
        spectrumKernel_ = cl.kernel("ocean.cl", "ocean_spectrum");
        heightKernel_ = cl.kernel("ocean.cl", "ocean_height");
        cl.queue().enqueueWriteBuffer(omegaBuffer_, CL_TRUE, 0, n * sizeof(float), omega_.data());
    });
    acquireLibrary(cl.programCache());
    try {
        // An out-of-place 2D inverse transform from the Hermitian half spectrum (kx index
        // 0..N/2, rows of N/2 + 1) to real heights, without the 1/N^2 scale: the height is the
        // plain sum of the modes. Baked now, so no frame pays for compiling it.
        const size_t lengths[2] = {size_t(N), size_t(N)};
        size_t inStrides[2] = {1, size_t(N / 2 + 1)}, outStrides[2] = {1, size_t(N)};
        checkFft(clfftCreateDefaultPlan(&plan_->handle, cl.context()(), CLFFT_2D, lengths), "creating the plan");
        checkFft(clfftSetPlanPrecision(plan_->handle, CLFFT_SINGLE), "setting the precision");
        checkFft(clfftSetLayout(plan_->handle, CLFFT_HERMITIAN_INTERLEAVED, CLFFT_REAL), "setting the layout");
        checkFft(clfftSetResultLocation(plan_->handle, CLFFT_OUTOFPLACE), "setting out-of-place");
        checkFft(clfftSetPlanInStride(plan_->handle, CLFFT_2D, inStrides), "setting the input strides");
        checkFft(clfftSetPlanOutStride(plan_->handle, CLFFT_2D, outStrides), "setting the output strides");
        checkFft(clfftSetPlanDistance(plan_->handle, size_t(N / 2 + 1) * N, size_t(N) * N), "setting the distances");
        checkFft(clfftSetPlanScale(plan_->handle, CLFFT_BACKWARD, 1.0f), "setting the scale");
        cl_command_queue queue = cl.queue()();
        withoutClfftWarnings(
            [&] { checkFft(clfftBakePlan(plan_->handle, 1, &queue, nullptr, nullptr), "baking the plan"); });
        uploadAmplitudes();
        compute();
    } catch (...) {
        plan_.reset();
        releaseLibrary();
        throw;
    }
}

OceanField::~OceanField() {
    plan_.reset();
    releaseLibrary();
}

void OceanField::setAmplitudes(const std::vector<std::complex<float>>& h0) {
    if (h0.size() != h0_.size())
        throw Error(str("OceanField::setAmplitudes: ", h0.size(), " amplitudes for ", h0_.size(), " wave vectors"));
    for (const auto& a : h0)
        if (!std::isfinite(a.real()) || !std::isfinite(a.imag()))
            throw Error("OceanField::setAmplitudes: amplitudes must be finite");
    h0_ = h0;
    uploadAmplitudes();
    compute();
}

void OceanField::uploadAmplitudes() {
    double variance = 0.0;
    for (const auto& a : h0_) variance += 2.0 * std::norm(a);
    sigma_ = float(std::sqrt(variance));
    scale_ = sigma_ > 0.0f ? 1.0f / (8.0f * sigma_) : 1.0f;
    clGuard("uploading the ocean spectrum", [&] {
        cl_.queue().enqueueWriteBuffer(h0Buffer_, CL_TRUE, 0, h0_.size() * sizeof(cl_float2), h0_.data());
    });
}

void OceanField::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("OceanField::step: dt must be positive and finite, got ", dt));
    time_ += dt;
    compute();
}

void OceanField::setTime(double seconds) {
    if (!std::isfinite(seconds)) throw Error(str("OceanField::setTime: time must be finite, got ", seconds));
    time_ = seconds;
    compute();
}

void OceanField::compute() {
    const int N = config_.size;
    // Every frequency is a multiple of 2 pi / T, so t may be taken modulo T, in double.
    const float t = float(std::fmod(time_, double(config_.repeatSeconds)) +
                          (time_ < 0 ? double(config_.repeatSeconds) : 0.0));
    clGuard("OceanField::step", [&] {
        cl::CommandQueue& q = cl_.queue();
        spectrumKernel_.setArg(0, h0Buffer_);
        spectrumKernel_.setArg(1, omegaBuffer_);
        spectrumKernel_.setArg(2, spectrum_);
        spectrumKernel_.setArg(3, N);
        spectrumKernel_.setArg(4, t);
        cl_.enqueue(spectrumKernel_, cl::NDRange(N / 2 + 1, N));
        cl_command_queue queue = q();
        cl_mem in = spectrum_(), out = field_();
        checkFft(clfftEnqueueTransform(plan_->handle, CLFFT_BACKWARD, 1, &queue, 0, nullptr, nullptr, &in, &out,
                                       nullptr),
                 "the inverse transform");
        heightKernel_.setArg(0, field_);
        heightKernel_.setArg(1, height_);
        heightKernel_.setArg(2, N);
        heightKernel_.setArg(3, scale_);
        cl_.enqueue(heightKernel_, cl::NDRange(N, N));
    });
}

} // namespace hfx
