#include "hfx/compute/NoiseField.h"

#include "hfx/core/Error.h"
#include "hfx/core/Names.h"

#include <cmath>

namespace hfx {

namespace {
constexpr NamedValue<NoiseKind> kKinds[] = {
    {NoiseKind::Perlin, "perlin"}, {NoiseKind::Simplex, "simplex"}, {NoiseKind::Psrd, "psrd"}};
constexpr NamedValue<Fractal> kFractals[] = {
    {Fractal::Fbm, "fbm"}, {Fractal::Ridged, "ridged"}, {Fractal::Turbulence, "turbulence"}};
} // namespace

NoiseKind parseNoiseKind(const std::string& name) { return parseName(kKinds, name, "noise"); }

Fractal parseFractal(const std::string& name) { return parseName(kFractals, name, "fractal"); }

float NoiseConfig::frequencyY() const {
    const float f = frequency * float(height) / float(width);
    if (!wrapsV(edges)) return f;
    const float whole = std::max(1.0f, std::round(f));
    return kind == NoiseKind::Psrd ? std::max(2.0f, 2.0f * std::round(f / 2.0f)) : whole;
}

void NoiseConfig::validate() const {
    if (width < 2 || height < 2 || width > 8192 || height > 8192)
        throw Error(str("NoiseConfig size must be in 2..8192, got ", width, "x", height));
    if (!(frequency > 0.0f) || frequency > 4096.0f)
        throw Error(str("NoiseConfig.frequency must be in (0, 4096], got ", frequency));
    if (octaves < 1 || octaves > 16)
        throw Error(str("NoiseConfig.octaves must be in [1, 16], got ", octaves));
    if (!(lacunarity >= 1.0f) || lacunarity > 8.0f)
        throw Error(str("NoiseConfig.lacunarity must be in [1, 8], got ", lacunarity));
    if (!(gain > 0.0f) || gain > 1.0f)
        throw Error(str("NoiseConfig.gain must be in (0, 1], got ", gain));
    if (!(warp >= 0.0f) || warp > 64.0f)
        throw Error(str("NoiseConfig.warp must be in [0, 64], got ", warp));
    if (!std::isfinite(speed) || !std::isfinite(seed))
        throw Error(str("NoiseConfig.speed and seed must be finite, got ", speed, " and ", seed));
    if (edges != EdgeMode::Clamp) {
        if (kind == NoiseKind::Simplex)
            throw Error(str("NoiseConfig: simplex noise has no periodic variant (edges ", edgeModeName(edges),
                            "); use perlin or psrd, or edges = clamp"));
        if (kind == NoiseKind::Psrd && edges == EdgeMode::WrapU)
            throw Error("NoiseConfig: psrd noise tiles both ways or not at all; edges wrap-u needs perlin");
        if (frequency != std::round(frequency))
            throw Error(str("NoiseConfig.frequency must be a whole number when the edges wrap, got ", frequency));
        if (lacunarity != std::round(lacunarity))
            throw Error(str("NoiseConfig.lacunarity must be a whole number when the edges wrap, got ", lacunarity));
        if (kind == NoiseKind::Perlin && frequency * std::pow(lacunarity, octaves - 1) > 256.0f)
            throw Error(str("NoiseConfig: the finest octave's period ", frequency * std::pow(lacunarity, octaves - 1),
                            " exceeds Perlin's 256-cell lattice"));
    }
}

NoiseField::NoiseField(ClContext& cl, const NoiseConfig& config) : cl_(cl), config_(config) {
    config.validate();
    clGuard("creating the noise field", [&] {
        height_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE,
                             sizeof(float) * size_t(config.width) * config.height);
        // Correctly rounded division, so the kernel rounds as the C++ reference does.
        kernel_ = cl.kernel("noise.cl", "noise",
                            str("-cl-fp32-correctly-rounded-divide-sqrt -DKIND=", int(config.kind),
                                " -DFRACTAL=", int(config.fractal), " ", edgeOptions(config.edges)));
    });
    compute();
}

float NoiseField::timeCoordinate(double seconds) const {
    // Reduced in double to a true period of the noise in t, so float keeps its precision over
    // long runs: psrdnoise's rotation repeats every 2 pi; Perlin's lattice every 256 cells in
    // z; the skewed simplex lattice every 768 along z alone (shifts of 256, 256, 1024 after
    // skewing, all multiples of its 256-entry table).
    const double t = config_.seed + config_.speed * seconds;
    const double period = config_.kind == NoiseKind::Psrd      ? 2.0 * 3.14159265358979323846
                          : config_.kind == NoiseKind::Simplex ? 768.0
                                                               : 256.0;
    return float(std::fmod(t, period) + (t < 0 ? period : 0.0));
}

void NoiseField::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("NoiseField::step: dt must be positive and finite, got ", dt));
    time_ += dt;
    compute();
}

void NoiseField::setTime(double seconds) {
    if (!std::isfinite(seconds)) throw Error(str("NoiseField::setTime: time must be finite, got ", seconds));
    time_ = seconds;
    compute();
}

void NoiseField::compute() {
    clGuard("NoiseField::step", [&] {
        int a = 0;
        kernel_.setArg(a++, height_);
        kernel_.setArg(a++, config_.width);
        kernel_.setArg(a++, config_.height);
        kernel_.setArg(a++, config_.frequency);
        kernel_.setArg(a++, config_.frequencyY());
        kernel_.setArg(a++, timeCoordinate(time_));
        kernel_.setArg(a++, config_.octaves);
        kernel_.setArg(a++, config_.lacunarity);
        kernel_.setArg(a++, config_.gain);
        kernel_.setArg(a++, config_.warp);
        cl_.enqueue(kernel_, cl::NDRange(config_.width, config_.height));
    });
}

} // namespace hfx
