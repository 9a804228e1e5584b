#include "hfx/compute/OceanSpectrum.h"

#include "hfx/core/Error.h"
#include "hfx/core/Names.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hfx {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kPhillipsAlpha = 0.0081;
/// The dimensionless fetch g F / U^2 at which JONSWAP's peak, 22 g / U (gF/U^2)^-1/3, reaches
/// the fully developed Pierson-Moskowitz peak 0.855 g / U10: beyond it the wind adds nothing,
/// so the fetch laws are held there.
constexpr double kFullyDevelopedFetch = (22.0 / 0.855) * (22.0 / 0.855) * (22.0 / 0.855);

constexpr NamedValue<SpectrumShape> kShapes[] = {{SpectrumShape::Phillips, "phillips"},
                                                 {SpectrumShape::PiersonMoskowitz, "pierson-moskowitz"},
                                                 {SpectrumShape::Jonswap, "jonswap"},
                                                 {SpectrumShape::Tma, "tma"}};
constexpr NamedValue<Spreading> kSpreadings[] = {
    {Spreading::Cos2s, "cos2s"}, {Spreading::Hasselmann, "hasselmann"}, {Spreading::DonelanBanner, "donelan-banner"}};

double u195(double u10) { return 1.026 * u10; } // Bretschneider: the wind 19.5 m up

double dimensionlessFetch(const WaveSpectrum& s) {
    return std::min(kGravity * s.fetchKm * 1000.0 / (double(s.windSpeed) * s.windSpeed), kFullyDevelopedFetch);
}

/// Kitaigorodskii's depth factor: how much of a deep-water spectrum shallow water holds.
double depthFactor(double omega, double depth) {
    if (depth <= 0.0) return 1.0;
    const double wh = omega * std::sqrt(depth / kGravity);
    if (wh <= 1.0) return 0.5 * wh * wh;
    if (wh <= 2.0) return 1.0 - 0.5 * (2.0 - wh) * (2.0 - wh);
    return 1.0;
}

/// Q(s) cos^2s(theta / 2), through log-gamma so large exponents do not overflow.
double cos2s(double s, double theta) {
    const double q = std::exp(std::lgamma(s + 1.0) - std::lgamma(s + 0.5)) / (2.0 * std::sqrt(kPi));
    return q * std::pow(std::abs(std::cos(theta / 2.0)), 2.0 * s);
}

/// theta wrapped into [-pi, pi].
double wrapAngle(double theta) { return std::remainder(theta, 2.0 * kPi); }

} // namespace

const char* spectrumShapeName(SpectrumShape shape) { return nameOf(kShapes, shape); }
SpectrumShape parseSpectrumShape(const char* name) { return parseName(kShapes, name, "spectrum"); }
const char* spreadingName(Spreading spreading) { return nameOf(kSpreadings, spreading); }
Spreading parseSpreading(const char* name) { return parseName(kSpreadings, name, "spreading"); }

void WaveSpectrum::validate(const char* what) const {
    if (!(windSpeed > 0.0f) || windSpeed > 100.0f)
        throw Error(str(what, ".windSpeed must be in (0, 100] m/s, got ", windSpeed));
    if (!std::isfinite(direction)) throw Error(str(what, ".direction must be finite, got ", direction));
    if (!(fetchKm > 0.0f) || fetchKm > 100000.0f)
        throw Error(str(what, ".fetchKm must be in (0, 100000], got ", fetchKm));
    if (!(peakEnhancement >= 1.0f) || peakEnhancement > 20.0f)
        throw Error(str(what, ".peakEnhancement must be in [1, 20], got ", peakEnhancement));
    if (!(spreadExponent > 0.0f) || spreadExponent > 500.0f)
        throw Error(str(what, ".spreadExponent must be in (0, 500], got ", spreadExponent));
    if (!(energy >= 0.0f) || !std::isfinite(energy)) throw Error(str(what, ".energy must be >= 0, got ", energy));
}

double WaveSpectrum::peakFrequency() const {
    const double U = windSpeed;
    switch (shape) {
    case SpectrumShape::Phillips: return std::pow(0.8, 0.25) * kGravity / U;
    case SpectrumShape::PiersonMoskowitz: return std::pow(0.8 * 0.74, 0.25) * kGravity / u195(U);
    case SpectrumShape::Jonswap:
    case SpectrumShape::Tma: return 22.0 * kGravity / U * std::pow(dimensionlessFetch(*this), -1.0 / 3.0);
    }
    return 1.0;
}

double WaveSpectrum::frequencySpectrum(double omega, double depth) const {
    if (!(omega > 0.0) || energy == 0.0f) return 0.0;
    const double g = kGravity, U = windSpeed;
    const double tail = g * g / std::pow(omega, 5.0);
    switch (shape) {
    case SpectrumShape::Phillips: return energy * kPhillipsAlpha * tail * std::exp(-std::pow(g / (U * omega), 4.0));
    case SpectrumShape::PiersonMoskowitz:
        return energy * kPhillipsAlpha * tail * std::exp(-0.74 * std::pow(g / (u195(U) * omega), 4.0));
    case SpectrumShape::Jonswap:
    case SpectrumShape::Tma: {
        const double wp = peakFrequency();
        const double alpha = 0.076 * std::pow(dimensionlessFetch(*this), -0.22);
        const double sigma = omega <= wp ? 0.07 : 0.09;
        const double r = std::exp(-(omega - wp) * (omega - wp) / (2.0 * sigma * sigma * wp * wp));
        const double s = alpha * tail * std::exp(-1.25 * std::pow(wp / omega, 4.0)) * std::pow(peakEnhancement, r);
        return energy * s * (shape == SpectrumShape::Tma ? depthFactor(omega, depth) : 1.0);
    }
    }
    return 0.0;
}

double WaveSpectrum::spread(double omega, double theta) const {
    theta = wrapAngle(theta);
    const double ratio = omega / peakFrequency();
    switch (spreading) {
    case Spreading::Cos2s: return cos2s(spreadExponent, theta);
    case Spreading::Hasselmann: {
        const double cp = kGravity / peakFrequency();
        const double s = ratio < 1.05 ? 6.97 * std::pow(ratio, 4.06)
                                      : 9.77 * std::pow(ratio, -2.33 - 1.45 * (windSpeed / cp - 1.17));
        return cos2s(std::clamp(s, 0.05, 500.0), theta);
    }
    case Spreading::DonelanBanner: {
        const double b = ratio < 0.95  ? 2.61 * std::pow(ratio, 1.3)
                         : ratio < 1.6 ? 2.28 * std::pow(ratio, -0.65)
                                       : std::pow(10.0, -0.4 + 0.8393 * std::exp(-0.567 * std::log(ratio * ratio)));
        const double sech = 1.0 / std::cosh(b * theta);
        return b / (2.0 * std::tanh(b * kPi)) * sech * sech;
    }
    }
    return 0.0;
}

void SeaState::validate() const {
    wind.validate("SeaState.wind");
    swell.validate("SeaState.swell");
    if (!(depthMeters >= 0.0f) || !std::isfinite(depthMeters))
        throw Error(str("SeaState.depthMeters must be >= 0 (0: deep water), got ", depthMeters));
}

double dispersion(double k, double depth) {
    return std::sqrt(kGravity * k * (depth > 0.0 ? std::tanh(k * depth) : 1.0));
}

double dispersionSlope(double k, double depth) {
    if (k <= 0.0) return 0.0;
    const double w = dispersion(k, depth);
    if (depth <= 0.0) return 0.5 * w / k;
    const double t = std::tanh(k * depth);
    return kGravity * (t + k * depth * (1.0 - t * t)) / (2.0 * w);
}

double SeaState::density(double kx, double ky) const {
    const double k = std::hypot(kx, ky);
    if (k == 0.0) return 0.0;
    const double w = dispersion(k, depthMeters), jacobian = dispersionSlope(k, depthMeters) / k;
    const double theta = std::atan2(ky, kx);
    double psi = 0.0;
    for (const WaveSpectrum* s : {&wind, &swell})
        if (s->energy > 0.0f)
            psi += s->frequencySpectrum(w, depthMeters) * s->spread(w, theta - s->direction) * jacobian;
    return psi;
}

double SeaState::variance(double kMin, double kMax) const {
    // Psi integrates over angle to S(w) dw/dk (the spreadings integrate to 1; a test holds them
    // to it), so the variance is the integral of S over the band's frequencies: Simpson's rule in
    // log w, fine enough that the quadrature is exact to far below the 1% the cascades must meet.
    const double w0 = dispersion(std::max(kMin, 1e-9), depthMeters), w1 = dispersion(kMax, depthMeters);
    constexpr int n = 20000;
    const double a = std::log(w0), h = (std::log(w1) - a) / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double w = std::exp(a + h * i);
        double f = 0.0;
        for (const WaveSpectrum* s : {&wind, &swell}) f += s->frequencySpectrum(w, depthMeters);
        f *= w; // dw = w d(log w)
        sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return sum * h / 3.0;
}

float beaufortWindSpeed(int force) {
    // The middle of each force's range of U10 (m/s); 12 has no upper end.
    static constexpr float kMiddle[] = {0.25f, 1.0f, 2.5f, 4.4f, 6.7f, 9.4f, 12.3f, 15.5f, 19.0f, 22.6f, 26.5f, 30.6f, 34.0f};
    if (force < 0 || force > 12) throw Error(str("Beaufort force must be in 0..12, got ", force));
    return kMiddle[force];
}

} // namespace hfx
