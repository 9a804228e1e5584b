#pragma once
// Ocean wave spectra in physical units, for OceanField. A sea state is a wind sea plus an
// optional swell, each a frequency spectrum S(w) (m^2 s) times a directional spreading D(w, theta)
// that integrates to 1 over the circle; the wave-number density the field samples is
//
//     Psi(kx, ky) = S(w) D(w, theta) (dw/dk) / k      (m^4: Psi dkx dky is a variance)
//
// with w(k) = sqrt(g k tanh(k d)) on water of depth d (deep water when d = 0).
//
//   Phillips            S = a g^2 w^-5 exp(-(g / (U w))^4), a = 0.0081 (Tessendorf's P(k) in w)
//   PiersonMoskowitz    S = a g^2 w^-5 exp(-0.74 (g / (U19.5 w))^4): a fully developed sea,
//                       Hs = 0.21 U19.5^2 / g (U19.5 = 1.026 U10)
//   Jonswap             fetch-limited (Hasselmann et al. 1973): a = 0.076 (U^2 / (F g))^0.22,
//                       wp = 22 (g^2 / (U F))^(1/3), peak enhancement gamma^r; the fetch laws
//                       stop where wp reaches the fully developed peak 0.855 g / U10
//   Tma                 JONSWAP times Kitaigorodskii's depth factor (Bouws et al. 1985)
//
//   Cos2s               Q(s) cos^2s(theta / 2) (Longuet-Higgins 1963), s = spreadExponent
//   Hasselmann          cos2s with s from w / wp (Hasselmann et al. 1980)
//   DonelanBanner       b / (2 tanh(b pi)) sech^2(b theta), b from w / wp (Donelan et al. 1985,
//                       Banner 1990 above 1.6 wp)
//
// Thread: any (plain values and functions).

#include <cstdint>

namespace hfx {

inline constexpr double kGravity = 9.81; ///< m/s^2

enum class SpectrumShape { Phillips, PiersonMoskowitz, Jonswap, Tma };
enum class Spreading { Cos2s, Hasselmann, DonelanBanner };

/// "phillips", "pierson-moskowitz", "jonswap", "tma" and "cos2s", "hasselmann", "donelan-banner";
/// the parses throw hfx::Error listing the known names.
const char* spectrumShapeName(SpectrumShape shape);
SpectrumShape parseSpectrumShape(const char* name);
const char* spreadingName(Spreading spreading);
Spreading parseSpreading(const char* name);

struct WaveSpectrum {
    SpectrumShape shape = SpectrumShape::Jonswap;
    float windSpeed = 10.0f;       ///< U10, m/s: the wind 10 m above the water
    float direction = 0.0f;        ///< radians from +u: where the waves travel
    float fetchKm = 100.0f;        ///< Jonswap, Tma: how far the wind has blown over water
    float peakEnhancement = 3.3f;  ///< Jonswap, Tma: gamma (1 is Pierson-Moskowitz's shape)
    Spreading spreading = Spreading::DonelanBanner;
    float spreadExponent = 10.0f;  ///< Cos2s: s; larger is narrower (swell: 30 and more)
    float energy = 1.0f;           ///< scales the variance (0 turns the spectrum off)
    /// Throws hfx::Error naming `what`'s bad field and its value ("swell.windSpeed").
    void validate(const char* what) const;

    /// The peak frequency w_p (rad/s).
    double peakFrequency() const;
    /// S(w), m^2 s, on water of depth `depth` metres (0: deep; only Tma reads it).
    double frequencySpectrum(double omega, double depth = 0.0) const;
    /// D(w, theta): theta measured from `direction`; integrates to 1 over [-pi, pi].
    double spread(double omega, double theta) const;
};

/// A wind sea and, with energy > 0, a swell from elsewhere: long, narrow, its own direction.
struct SeaState {
    WaveSpectrum wind;
    WaveSpectrum swell{.windSpeed = 14.0f, .direction = 1.2f, .fetchKm = 2000.0f, .peakEnhancement = 6.0f,
                       .spreading = Spreading::Cos2s, .spreadExponent = 40.0f, .energy = 0.0f};
    float depthMeters = 0.0f; ///< water depth; 0 = deep. Sets the dispersion and Tma's factor.
    void validate() const;
    /// Psi(kx, ky), m^4.
    double density(double kx, double ky) const;
    /// The variance of the sea between wave numbers kMin and kMax (rad/m), by quadrature of
    /// Psi over the annulus: the truth the cascades' discrete sums are held to.
    double variance(double kMin, double kMax) const;
};

/// w(k) = sqrt(g k tanh(k d)); d = 0 is deep water (tanh = 1).
double dispersion(double k, double depth);
/// dw/dk of the same relation.
double dispersionSlope(double k, double depth);

/// The Beaufort scale's wind (U10, m/s, the middle of each force's range), force 0 to 12.
float beaufortWindSpeed(int force);

} // namespace hfx
