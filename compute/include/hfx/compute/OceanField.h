#pragma once
// Tessendorf's statistical FFT ocean ("Simulating Ocean Water", 2001): a Phillips or JONSWAP
// spectrum of wind waves on a tileable patch, animated with the deep-water dispersion relation
// w^2 = g k (quantised to a repeat period, so the animation loops seamlessly and float phases
// stay exact), transformed to heights each frame by an inverse 2D FFT on the device (clFFT).
//
// Heights are stored as h = 0.5 + height / (8 sigma), sigma the spectrum's RMS height, clamped
// to [0,1] (a 4-sigma crest reaches 1); heightScale() gives that factor, sigmaMeters() sigma.
// Thread: the thread that owns the ClContext.

#include "hfx/compute/HeightSource.h"

#include <complex>
#include <cstdint>
#include <memory>
#include <vector>

namespace hfx {

enum class OceanSpectrum { Phillips, Jonswap };

struct OceanConfig {
    int size = 256;                 ///< texels per edge, a power of two in [8, 4096]
    float patchMeters = 100.0f;     ///< physical edge length of the tileable patch
    OceanSpectrum spectrum = OceanSpectrum::Phillips;
    float windSpeed = 12.0f;        ///< m/s at 10 m
    float windDirection = 0.6f;     ///< radians from +u
    float fetchKm = 200.0f;         ///< JONSWAP: distance the wind has blown over water
    float directionality = 2.0f;    ///< Phillips: |k.w|^directionality
    float smallWaveMeters = 0.05f;  ///< waves shorter than this are suppressed
    float repeatSeconds = 200.0f;   ///< loop period of the animation
    std::uint64_t seed = 1;
    void validate() const;
};

class OceanField final : public HeightSource {
public:
    OceanField(ClContext& cl, const OceanConfig& config);
    ~OceanField() override;
    OceanField(const OceanField&) = delete;
    OceanField& operator=(const OceanField&) = delete;

    void step(double dt) override;
    void setTime(double seconds);
    /// Changes the wind (m/s, radians from +u) and regenerates the spectrum from the same random
    /// draws, so the sea changes character without jumping; throws and changes nothing on bad
    /// values. Heights are renormalised to the new sigma (see heightScale()).
    void setWind(float speed, float direction);
    /// h0(k) of a configuration, in FFT index order (what the constructor draws).
    static std::vector<std::complex<float>> spectrumAmplitudes(const OceanConfig& config);
    double time() const { return time_; }

    const cl::Buffer& buffer() const override { return height_; }
    /// The inverse transform's sum of the modes, N x N floats (height in the spectrum's units,
    /// before heightScale() maps it into [0,1]).
    const cl::Buffer& rawHeight() const { return field_; }
    int width() const override { return config_.size; }
    int height() const override { return config_.size; }
    EdgeMode edges() const override { return EdgeMode::Wrap; }
    const OceanConfig& config() const { return config_; }

    /// h0(k) at FFT index order, and the quantised angular frequencies.
    const std::vector<std::complex<float>>& amplitudes() const { return h0_; }
    const std::vector<float>& frequencies() const { return omega_; }
    /// Replaces h0 (custom spectra, tests); rescales the stored heights to the new sigma.
    void setAmplitudes(const std::vector<std::complex<float>>& h0);
    float sigmaMeters() const { return sigma_; }
    float heightScale() const { return scale_; }
    /// w(k) = sqrt(g |k|) rounded to a multiple of 2 pi / repeatSeconds.
    static float quantisedOmega(double k, double repeatSeconds);

private:
    void compute();
    void uploadAmplitudes();

    struct Plan;
    ClContext& cl_;
    OceanConfig config_;
    std::vector<std::complex<float>> h0_;
    std::vector<float> omega_;
    float sigma_ = 0.0f, scale_ = 0.0f;
    cl::Buffer h0Buffer_, omegaBuffer_, spectrum_, field_, height_;
    cl::Kernel spectrumKernel_, heightKernel_;
    std::unique_ptr<Plan> plan_;
    double time_ = 0.0;
};

} // namespace hfx
