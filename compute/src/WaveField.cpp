#include "hfx/compute/WaveField.h"

#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <cmath>
#include <numbers>

namespace hfx {

void WaveConfig::validate() const {
    if (size < 2 || size > 8192)
        throw Error(str("WaveConfig.size must be in [2, 8192], got ", size));
    if (waveCount < 1 || waveCount > 1024)
        throw Error(str("WaveConfig.waveCount must be in [1, 1024], got ", waveCount));
    if (!(patchMeters > 0.0f) || !std::isfinite(patchMeters))
        throw Error(str("WaveConfig.patchMeters must be positive, got ", patchMeters));
    if (!std::isfinite(windDirection))
        throw Error(str("WaveConfig.windDirection must be finite, got ", windDirection));
    if (!(spread >= 0.0f) || spread > std::numbers::pi_v<float>)
        throw Error(str("WaveConfig.spread must be in [0, pi], got ", spread));
    if (minCycles < 1 || maxCycles < minCycles || maxCycles > size / 2)
        throw Error(str("WaveConfig cycles must satisfy 1 <= minCycles <= maxCycles <= size/2, got ",
                        minCycles, "..", maxCycles, " for size ", size));
    if (!(steepness >= 0.0f) || steepness > 0.25f)
        throw Error(str("WaveConfig.steepness must be in [0, 0.25], got ", steepness));
}

std::vector<Wave> WaveField::makeWaves(const WaveConfig& config) {
    config.validate();
    SplitMix64 random(config.seed);
    std::vector<Wave> waves;
    constexpr double g = 9.81, twoPi = 2.0 * std::numbers::pi;
    for (int i = 0; i < config.waveCount; ++i) {
        // Wavelengths spread geometrically; directions around the wind.
        const double t = config.waveCount > 1 ? double(i) / (config.waveCount - 1) : 0.0;
        const double cycles = config.minCycles * std::pow(double(config.maxCycles) / config.minCycles, t);
        const double angle = config.windDirection + (2.0 * random.next() - 1.0) * config.spread;
        float m = float(std::round(cycles * std::cos(angle)));
        float n = float(std::round(cycles * std::sin(angle)));
        if (m == 0.0f && n == 0.0f) m = 1.0f;
        const double k = twoPi * std::hypot(m, n) / config.patchMeters;
        // Amplitude proportional to wavelength keeps the steepness of every wave alike.
        const float amplitude = float(1.0 / std::hypot(m, n)) * float(0.75 + 0.5 * random.next());
        waves.push_back({m, n, amplitude, float(std::sqrt(g * k)), float(twoPi * random.next())});
    }
    return waves;
}

float WaveField::phaseAt(const Wave& wave, double seconds) {
    const double twoPi = 2.0 * std::numbers::pi;
    double phase = std::fmod(double(wave.phase) - double(wave.omega) * seconds, twoPi);
    if (phase < 0.0) phase += twoPi;
    return float(phase);
}

float WaveField::inverseTotalAmplitude(const std::vector<Wave>& waves) {
    double total = 0.0;
    for (const Wave& w : waves) total += w.amplitude;
    return float(1.0 / total);
}

WaveField::WaveField(ClContext& cl, const WaveConfig& config)
    : cl_(cl), config_(config), waves_(makeWaves(config)), packed_(waves_.size()) {
    clGuard("creating the waves field", [&] {
        waveBuffer_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY, packed_.size() * sizeof(cl_float4));
        const size_t table = sizeof(cl_float2) * waves_.size() * size_t(config.size);
        columns_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, table);
        rows_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, table);
        tables_ = cl.kernel("waves.cl", "wave_tables");
        height_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE,
                             sizeof(float) * size_t(config.size) * config.size);
        kernel_ = cl.kernel("waves.cl", "waves");
    });
    compute();
}

void WaveField::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("WaveField::step: dt must be positive and finite, got ", dt));
    time_ += dt;
    compute();
}

void WaveField::setTime(double seconds) {
    if (!std::isfinite(seconds))
        throw Error(str("WaveField::setTime: time must be finite, got ", seconds));
    time_ = seconds;
    compute();
}

void WaveField::compute() {
    for (size_t i = 0; i < waves_.size(); ++i) {
        const Wave& w = waves_[i];
        packed_[i] = {{w.m, w.n, w.amplitude, phaseAt(w, time_)}};
    }
    clGuard("WaveField::step", [&] {
        cl::CommandQueue& q = cl_.queue();
        // Blocking: packed_ is rewritten by the next step, so the copy must be taken now.
        q.enqueueWriteBuffer(waveBuffer_, CL_TRUE, 0, packed_.size() * sizeof(cl_float4),
                             packed_.data());
        tables_.setArg(0, columns_);
        tables_.setArg(1, rows_);
        tables_.setArg(2, config_.size);
        tables_.setArg(3, waveBuffer_);
        cl_.enqueue(tables_, cl::NDRange(config_.size, waves_.size()));
        kernel_.setArg(0, height_);
        kernel_.setArg(1, config_.size);
        kernel_.setArg(2, columns_);
        kernel_.setArg(3, rows_);
        kernel_.setArg(4, waveBuffer_);
        kernel_.setArg(5, int(waves_.size()));
        kernel_.setArg(6, config_.steepness);
        kernel_.setArg(7, inverseTotalAmplitude(waves_));
        cl_.enqueue(kernel_, cl::NDRange(config_.size, config_.size));
    });
}

} // namespace hfx
