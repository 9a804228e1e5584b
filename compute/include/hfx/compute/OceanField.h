#pragma once
// Tessendorf's statistical FFT ocean ("Simulating Ocean Water", 2001) in cascades, with choppy
// waves and persistent foam, on the OpenCL device (the inverse FFTs through VkFFT: InverseRealFft).
//
// The sea state (OceanSpectrum.h: physical spectra, spreading, swell, depth) is sampled on 1 to 4
// cascades: square periodic patches whose edges shrink by `cascadeRatio` (5.27 by default, so no
// two lengths share a common factor and their sum never repeats) and whose wave-number bands do
// not overlap: cascade i keeps k in [k_i, k_i+1), every wave at least 8 of its texels long and
// at least 6 of its lattice steps from the origin. The bands' variances add up to the sea's
// (Parseval; tested).
//
// Each step, per cascade: the spectrum at time t for h, and for the horizontal displacement
// D(k) = i k/|k| h(k); one batched inverse transform; on the Lagrangian grid (the undisplaced
// points x0) the Jacobian J of x0 -> x0 + lambda D(x0) by fourth-order differences, and the foam,
// injected where J < threshold, halving every halfLife seconds, drifting downwind; then the
// Eulerian field the renderer traces: for each texel x, the point x0 displaced onto it by a few
// Newton steps on x0 + lambda D(x0) = x, then the height h(x0) and the foam there. A single mode is the
// trochoidal (Gerstner) wave: x = x0 - lambda k^ A sin(theta), h = A cos(theta),
// J = 1 - lambda k A cos(theta) (tested to 1e-4).
//
// Where J > 0 the map is invertible and the Eulerian height is the surface's; where it folds
// (J <= 0, an overhang no height field holds) the steps fall back to the fixed point
// x0 <- x - lambda D(x0), which settles on one of the layers over x,
// and the crest is drawn as the height field through it, sharp and possibly clipped: the foam
// marks exactly those places.
//
// Time is a pure input: the heights and displacements at t depend on the seed, the sea state
// and t alone (setTime jumps there; tested bit for bit). Foam is history: it is stepped with the
// field, and setTime restarts it clear.
//
// Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"
#include "hfx/compute/InverseRealFft.h"
#include "hfx/compute/OceanSpectrum.h"

#include <complex>
#include <cstdint>
#include <memory>
#include <vector>

namespace hfx {

/// Whitecaps. By default (threshold < 0) each cascade's threshold on J is set from the sea
/// state so that the area where foam is injected follows Monahan's whitecap coverage,
/// W = 3.84e-6 U10^3.41 (Monahan & O'Muircheartaigh 1980; 1% at 10 m/s, 4.5% at 15.5): W is
/// shared among the cascades by their variance of J - 1 (about lambda |k| h, which the spectrum
/// gives), and each cascade's threshold is the quantile of its own J that leaves its share below,
/// taken from the field when the spectrum is made or changed (J's statistics do not change with
/// time). An explicit threshold (>= 0) is used as it is, by every cascade.
struct FoamConfig {
    float threshold = -1.0f; ///< foam is injected where J falls below this (1 is flat water); < 0: Monahan
    float coverage = 1.0f;   ///< scales Monahan's coverage (automatic thresholds only)
    /// Foam added per second per unit of threshold - J; with automatic thresholds per unit of
    /// (threshold - J) / sigma_J, so a cascade's foam builds alike whatever its steepness.
    float injection = 4.0f;
    float halfLife = 4.0f;   ///< seconds for foam to halve
    /// Seconds for the young share of the foam to halve: what a breaking crest injects is young
    /// (a whitecap's dense white, Monahan's stage A) and ages into residual foam (stage B), which
    /// the water shading draws as a lace that opens as it thins. The foam's halfLife where that
    /// is shorter.
    float youngHalfLife = 1.0f;
    float drift = 0.03f;     ///< downwind drift, as a fraction of the wind speed
    /// Metres: waves shorter than this break without entraining air (microscale breaking, up to
    /// O(1 m) long: Jessup, Zappa and Yeh 1997) and make no whitecap. The automatic thresholds
    /// share Monahan's coverage among the cascades by the J variance of their waves at least this
    /// long (0: of all their waves, as the finest cascade's centimetre waves strewed specks).
    float shortestWhitecap = 1.0f;
    void validate() const;   ///< throws hfx::Error naming the bad field and its value
};

struct OceanConfig {
    int size = 256;             ///< texels per cascade edge, a power of two in [16, 1024]
    int cascades = 4;           ///< 1 to 4
    /// The largest cascade's edge in metres; 0: 8 peak wavelengths of the wind sea (at least
    /// 200 m), so the peak is resolved and the patch repeats far apart.
    float patchMeters = 0.0f;
    float cascadeRatio = 5.27f; ///< each cascade's edge over the next's, in (2, 8]
    SeaState sea;
    float choppiness = 1.0f;    ///< lambda: 0 is plain heights; near 1 the crests sharpen, above they fold
    float repeatSeconds = 200.0f; ///< frequencies are multiples of 2 pi / this: the sea loops
    std::uint64_t seed = 1;
    FoamConfig foam;
    void validate() const;      ///< throws hfx::Error naming the bad field and its value
    /// The cascades' edges in metres, largest first (patchMeters resolved).
    std::vector<float> cascadeLengths() const;
};

/// One cascade: a periodic size x size patch of the sea, its wave-number band and its fields.
struct OceanCascade {
    float patchMeters = 0.0f;
    float kMin = 0.0f, kMax = 0.0f;   ///< its band (rad/m): k in [kMin, kMax)
    float sigma = 0.0f;               ///< its height's RMS (m), the spectrum's expected value
    float sigmaJ = 0.0f;              ///< RMS of its J - 1 (about lambda |k| h), the spectrum's expected value
    /// ... of its waves at least FoamConfig::shortestWhitecap long: those that whiten as they break.
    float sigmaJWhitecaps = 0.0f;
    float foamThreshold = 0.0f;       ///< where foam is injected: J below this
    float foamGain = 0.0f;            ///< foam per second per unit of threshold - J
    float scale = 0.0f;               ///< stored height h = 0.5 + metres * scale (1 / 8 sigma)
    std::vector<std::complex<float>> h0; ///< h0(k), FFT index order, zero outside the band
    /// The spectrum a wind change blends from (OceanField::setWind): h0 at time t is
    /// hfx_ocean_blend(h0From, h0, blend(t)), energy mixed linearly and each k's phase kept, so
    /// waves fade in and out where they are.
    std::vector<std::complex<float>> h0From;
    std::vector<float> omega;         ///< w(k), quantised to multiples of 2 pi / repeatSeconds
    cl::Buffer height;                ///< Eulerian h in [0,1] (size^2 floats): what Sobel and the GL surface take
    cl::Buffer meters;                ///< the same heights in metres, unclamped
    /// Eulerian foam as RGBA8: coverage in alpha, its young share (OceanField::youngFoam) in red,
    /// green and blue 255; read young / coverage for the foam's freshness after any filtering.
    cl::Buffer foamColor;
    cl::Buffer lagrangian;            ///< h, Dx, Dy on the Lagrangian grid (metres), 3 size^2 blocks
    cl::Buffer jacobian;              ///< J on the Lagrangian grid
    cl::Buffer packed;                ///< the Lagrangian grid packed for the resample (OceanMath.h, hfx_ocean_pack)
    cl::Buffer foam[2];               ///< foam coverage on the Lagrangian grid, this step's and the last
    cl::Buffer young[2];              ///< its young part (FoamConfig::youngHalfLife), likewise
    cl::Buffer h0Device, h0FromDevice, omegaDevice; ///< h0, h0From and omega on the device
    /// sum 2 |h0From|^2 and sum 2 |h0|^2: sigma^2 at blend s is their mix.
    double varianceFrom = 0.0, varianceTo = 0.0;
};

/// A wind change in progress: the spectrum blends from OceanCascade::h0From to h0 between
/// `start` and start + `seconds` (of the field's time), along a smoothstep.
struct WindBlend {
    double start = 0.0;
    double seconds = 0.0;
    /// 0 before the change, 1 once it is done.
    double at(double time) const;
};

class OceanField {
public:
    OceanField(ClContext& cl, const OceanConfig& config);
    ~OceanField();
    OceanField(const OceanField&) = delete;
    OceanField& operator=(const OceanField&) = delete;

    /// Advances by dt seconds (> 0, finite): the fields at the new time, the foam stepped by dt.
    void step(double dt);
    /// The fields at `seconds` (finite), without stepping; the foam restarts clear.
    void setTime(double seconds);
    /// The foam as `seconds` (0 to 600) of the present wind would have left it: the field runs from
    /// time() - seconds to time() in steps of at most `dt` (0.25 s), the foam bit for bit as
    /// step() leaves it (the heights resampled only after the last step: no other needs them),
    /// and ends with the fields at time() exactly as before. A sea that has blown a while, for a
    /// first frame (a clear start shows a storm's whitecaps only after their half-lives). Before
    /// any wind change: a blend in progress would be run again.
    void settleFoam(double seconds, double dt = 0.25);
    double time() const { return time_; }

    /// Changes the wind sea (m/s, radians from +u): the spectrum of that wind, from the same
    /// random phases, is blended in over `blendSeconds` of the field's time (0: at once). The
    /// wave vectors stay where they are, so nothing rotates about the patch's origin: waves of
    /// the old direction fade out where they are and the new ones fade in. A change during a
    /// blend starts from the sea as it is then. Throws and changes nothing on bad values.
    void setWind(float speed, float direction, double blendSeconds = 0.0);
    const WindBlend& windBlend() const { return blend_; }
    /// Replaces one cascade's h0 (custom spectra, tests); its sigma and scale follow.
    void setAmplitudes(int cascade, const std::vector<std::complex<float>>& h0);

    int cascadeCount() const { return int(cascades_.size()); }
    const OceanCascade& cascade(int i) const { return cascades_.at(size_t(i)); }
    /// A cascade's foam coverage on the Lagrangian grid after the last step (size^2 floats).
    const cl::Buffer& foam(int cascade) const { return cascades_.at(size_t(cascade)).foam[foamFront_]; }
    /// Its young part (size^2 floats, at most the foam): injected with it, halving every
    /// FoamConfig::youngHalfLife seconds, carried and drifting as the foam is.
    const cl::Buffer& youngFoam(int cascade) const {
        return cascades_.at(size_t(cascade)).young[foamFront_];
    }
    const OceanConfig& config() const { return config_; }
    /// The RMS height of the whole sea (m): the cascades' sigmas in quadrature.
    float sigmaMeters() const;
    /// Monahan's whitecap coverage for a wind of U10 m/s: 3.84e-6 U^3.41, at most 1.
    static double whitecapCoverage(double windSpeed);

    /// h0(k) of a configuration's cascade, in FFT index order (what the constructor draws).
    static std::vector<std::complex<float>> spectrumAmplitudes(const OceanConfig& config, int cascade);
    /// w(k) rounded down to a multiple of 2 pi / repeatSeconds, on water of the given depth.
    static float quantisedOmega(double k, double depth, double repeatSeconds);
    /// The wave vector (rad/m) of FFT index (x, y) on a cascade of edge L: n = x for x < N/2,
    /// else x - N (likewise y).
    static void waveVector(int x, int y, int n, double patchMeters, double& kx, double& ky);
    /// The time the spectrum is evaluated at: `seconds` modulo repeatSeconds (every frequency
    /// is a multiple of 2 pi / repeatSeconds), so omega t stays exact in float over any run.
    static float periodicTime(double seconds, float repeatSeconds);
    /// Newton steps of the Eulerian resample (x0 + lambda D(x0) = x), at most: quadratic
    /// convergence, so four reach float precision on steep unfolded waves (lambda k A = 0.75 in
    /// the tests); a texel stops once a step moves it less than HFX_OCEAN_NEWTON_TOLERANCE.
    static constexpr int eulerianIterations = 4;

private:
    void makeCascade(OceanCascade& c, float patchMeters, float kMin, float kMax);
    void uploadAmplitudes(OceanCascade& c);
    void setBlendedSigma(OceanCascade& c, double blend);
    void calibrateFoam();
    /// The fields at time_, the foam stepped by dt; `resample` false leaves the Eulerian fields
    /// (the heights, the foam's texels) as they were: settleFoam's steps, which only the foam's
    /// history needs.
    void compute(double dt, bool resample = true);

    ClContext& cl_;
    OceanConfig config_;
    std::vector<OceanCascade> cascades_;
    cl::Buffer spectrum_; ///< the half spectra of h, Dx, Dy, reused by every cascade
    cl::Kernel spectrumKernel_, lagrangianKernel_, eulerianKernel_;
    std::unique_ptr<InverseRealFft> fft_;
    int foamFront_ = 0;
    double time_ = 0.0;
    WindBlend blend_;
    bool calibrateAfterBlend_ = false;
};

} // namespace hfx
