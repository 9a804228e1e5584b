// The ocean's inverse FFT on the device (InverseRealFft, VkFFT) against a plain C++ DFT of the
// same Hermitian half spectra, against analytic single modes, and against Parseval's theorem; the
// gas's forward and inverse real FFT (RealFft) along the rows and along both axes against a plain
// DFT, and its inverse as the forward's, unscaled.

#include "support/Fixtures.h"

#include "hfx/compute/InverseRealFft.h"
#include "hfx/compute/RealFft.h"
#include "hfx/core/Error.h"

#include <algorithm>
#include <clocale>
#include <cstdio>
#include <cmath>
#include <complex>
#include <filesystem>
#include <locale.h>
#include <numbers>
#include <random>
#include <string>

namespace hfx::test {
namespace {

using Complex = std::complex<double>;

class InverseFft : public ClTest {
protected:
    /// The device's fields of `spectrum` (batch half spectra, rows of n/2 + 1).
    std::vector<float> transform(int n, int batch, const std::vector<std::complex<float>>& spectrum) {
        InverseRealFft fft(cl(), n, batch);
        EXPECT_EQ(spectrum.size() * sizeof(std::complex<float>), fft.spectrumBytes());
        cl::Buffer in(cl().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, fft.spectrumBytes(),
                      const_cast<std::complex<float>*>(spectrum.data()));
        cl::Buffer out(cl().context(), CL_MEM_READ_WRITE, fft.fieldBytes());
        fft.enqueue(in, out);
        return readFloats(cl(), out, fft.fieldBytes() / sizeof(float));
    }
};

/// The full spectrum's value at (kx, ky) from the half one: S(-k) = conj(S(k)).
Complex fullSpectrum(const std::vector<std::complex<float>>& half, int n, int b, int kx, int ky) {
    const int w = n / 2 + 1;
    const size_t base = size_t(b) * size_t(w) * size_t(n);
    if (kx <= n / 2) return Complex(half[base + size_t(ky) * w + size_t(kx)]);
    return std::conj(Complex(half[base + size_t((n - ky) % n) * w + size_t(n - kx)]));
}

/// The plain double-precision DFT: field(x, y) = sum_k S(k) e^{+2 pi i k.x / n}, real part (the
/// transform of a Hermitian spectrum is real; a spectrum that is not, at kx = 0 or n/2, is read as
/// C2R transforms read it: through its Hermitian part, which the real part is).
std::vector<double> referenceFields(const std::vector<std::complex<float>>& half, int n, int batch) {
    std::vector<double> out(size_t(batch) * size_t(n) * size_t(n));
    const double step = 2.0 * std::numbers::pi / n;
    for (int b = 0; b < batch; ++b)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                double sum = 0.0;
                for (int ky = 0; ky < n; ++ky)
                    for (int kx = 0; kx < n; ++kx)
                        sum += (fullSpectrum(half, n, b, kx, ky) * std::polar(1.0, step * (kx * x + ky * y))).real();
                out[(size_t(b) * n + size_t(y)) * n + size_t(x)] = sum;
            }
    return out;
}

/// A random half spectrum that is Hermitian where the half plane meets itself (kx = 0 and n/2),
/// so that it is the half of a real field's spectrum.
std::vector<std::complex<float>> randomHermitian(int n, int batch, unsigned seed) {
    std::mt19937 random(seed);
    std::normal_distribution<float> normal;
    const int w = n / 2 + 1;
    std::vector<std::complex<float>> s(size_t(batch) * size_t(w) * size_t(n));
    for (auto& v : s) v = {normal(random), normal(random)};
    for (int b = 0; b < batch; ++b)
        for (int kx : {0, n / 2})
            for (int ky = 0; ky < n; ++ky) {
                auto& v = s[(size_t(b) * n + size_t(ky)) * w + size_t(kx)];
                const auto& mirror = s[(size_t(b) * n + size_t((n - ky) % n)) * w + size_t(kx)];
                if ((n - ky) % n == ky) v = {v.real(), 0.0f};
                else if (ky > n / 2) v = std::conj(mirror);
            }
    return s;
}

TEST_F(InverseFft, MatchesAPlainDftOfTheSameSpectraAtEverySizeAndBatch) {
    for (auto [n, batch] : {std::pair{16, 1}, std::pair{32, 3}, std::pair{64, 2}}) {
        const auto spectrum = randomHermitian(n, batch, unsigned(n));
        const std::vector<float> device = transform(n, batch, spectrum);
        const std::vector<double> reference = referenceFields(spectrum, n, batch);
        double worst = 0.0, scale = 0.0;
        for (size_t i = 0; i < device.size(); ++i) {
            worst = std::max(worst, std::abs(device[i] - reference[i]));
            scale = std::max(scale, std::abs(reference[i]));
        }
        // float32 over log2(n^2) butterfly stages: a few ulps of the field's scale (about n).
        EXPECT_LT(worst, 2e-5 * scale * std::log2(double(n) * n)) << n << "x" << n << " batch " << batch;
        EXPECT_GT(scale, 1.0); // a field, not zeros
    }
}

TEST_F(InverseFft, ASingleModeIsItsCosineWaveAndTheConstantItsLevel) {
    constexpr int n = 256;
    const int w = n / 2 + 1;
    std::vector<std::complex<float>> spectrum(size_t(2) * w * n);
    spectrum[size_t(5) * w + 3] = {1.0f, 0.5f}; // batch 0: the mode (kx, ky) = (3, 5)
    spectrum[size_t(w) * n] = {2.0f, 0.0f};      // batch 1: the mean
    const std::vector<float> fields = transform(n, 2, spectrum);
    double worst = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            // S e^{i phi} + conj(S) e^{-i phi} = 2 Re(S e^{i phi}).
            const double phi = 2.0 * std::numbers::pi * (3.0 * x + 5.0 * y) / n;
            worst = std::max(worst, std::abs(fields[size_t(y) * n + x] - 2.0 * (std::cos(phi) - 0.5 * std::sin(phi))));
            worst = std::max(worst, std::abs(fields[size_t(n) * n + size_t(y) * n + x] - 2.0));
        }
    EXPECT_LT(worst, 1e-5);
}

TEST_F(InverseFft, KeepsParsevalsEnergy) {
    constexpr int n = 128, batch = 3;
    const auto spectrum = randomHermitian(n, batch, 11);
    const std::vector<float> fields = transform(n, batch, spectrum);
    for (int b = 0; b < batch; ++b) {
        double spatial = 0.0, spectral = 0.0;
        for (size_t i = 0; i < size_t(n) * n; ++i) spatial += double(fields[size_t(b) * n * n + i]) * fields[size_t(b) * n * n + i];
        for (int ky = 0; ky < n; ++ky)
            for (int kx = 0; kx < n; ++kx) spectral += std::norm(fullSpectrum(spectrum, n, b, kx, ky));
        // Unscaled inverse: sum |f|^2 = n^2 sum |S|^2.
        EXPECT_NEAR(spatial / (double(n) * n * spectral), 1.0, 1e-5) << "batch " << b;
    }
}

TEST_F(InverseFft, PlanningKeepsTheCallersLocale) {
    // A composite locale (one category apart, as GLFW's X11 start leaves it): VkFFT's code
    // generator sets "C" and restored the old one through a pointer that call had freed
    // (AddressSanitizer: a use after free; scripts/sanitize.sh). The plan leaves the locale as
    // the caller had it.
    const char* before = std::setlocale(LC_ALL, nullptr);
    const std::string original = before ? before : "C";
    if (!std::setlocale(LC_CTYPE, "C.UTF-8")) GTEST_SKIP() << "no C.UTF-8 locale here";
    const std::string composite = std::setlocale(LC_ALL, nullptr);
    EXPECT_NE(composite.find(';'), std::string::npos) << composite << ": not a composite locale";
    {
        InverseRealFft fft(cl(), 16, 1);
    }
    const char* after = std::setlocale(LC_ALL, nullptr);
    EXPECT_EQ(std::string(after ? after : ""), composite);
    std::setlocale(LC_ALL, original.c_str());
}

TEST_F(InverseFft, BadSizesAndBuffersAreRefusedByName) {
    EXPECT_NE(messageOf([&] { InverseRealFft(cl(), 100, 3); }).find("100"), std::string::npos);
    EXPECT_NE(messageOf([&] { InverseRealFft(cl(), 64, 0); }).find("batch"), std::string::npos);
    InverseRealFft fft(cl(), 64, 3);
    cl::Buffer small(cl().context(), CL_MEM_READ_WRITE, 1024);
    cl::Buffer fields(cl().context(), CL_MEM_READ_WRITE, fft.fieldBytes());
    const std::string m = messageOf([&] { fft.enqueue(small, fields); });
    EXPECT_NE(m.find("64x64"), std::string::npos) << m;
    EXPECT_NE(m.find(std::to_string(fft.spectrumBytes())), std::string::npos) << m;
}

/// A random W x H field's RealFft against the plain DFT: {the largest error of its half spectrum
/// over the largest value, the largest error of its inverse, unscaled, over the field's}.
/// `fft` is made by the caller (its plan is what a test may be about).
std::pair<double, double> realFftErrors(ClContext& cl, RealFft& fft, const std::vector<float>& field) {
    const int W = fft.width(), H = fft.height(), K = W / 2 + 1;
    const bool both = fft.axes() == RealFft::Axes::Both;
    cl::Buffer in(cl.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, fft.fieldBytes(),
                  const_cast<float*>(field.data()));
    cl::Buffer spectrum(cl.context(), CL_MEM_READ_WRITE, fft.spectrumBytes());
    cl::Buffer back(cl.context(), CL_MEM_READ_WRITE, fft.fieldBytes());
    fft.forward(in, spectrum);
    const std::vector<float> s = readFloats(cl, spectrum, fft.spectrumBytes() / sizeof(float));
    double worst = 0.0, largest = 0.0;
    for (int l = 0; l < H; ++l)
        for (int k = 0; k < K; ++k) {
            Complex dft = 0.0;
            for (int y = both ? 0 : l; y < (both ? H : l + 1); ++y)
                for (int x = 0; x < W; ++x) {
                    const double turns = double(k) * x / W + (both ? double(l) * y / H : 0.0);
                    dft += double(field[size_t(y) * W + x]) * std::polar(1.0, -2.0 * std::numbers::pi * turns);
                }
            const Complex got(s[2 * (size_t(l) * K + k)], s[2 * (size_t(l) * K + k) + 1]);
            worst = std::max(worst, std::abs(got - dft));
            largest = std::max(largest, std::abs(dft));
        }
    fft.inverse(spectrum, back);
    const std::vector<float> b = readFloats(cl, back, field.size());
    const double scale = both ? double(W) * H : double(W);
    double roundTrip = 0.0;
    for (size_t i = 0; i < field.size(); ++i) roundTrip = std::max(roundTrip, std::abs(b[i] / scale - field[i]));
    return {worst / largest, roundTrip};
}

std::vector<float> randomField(int width, int height, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<float> field(size_t(width) * height);
    for (float& f : field) f = unit(random);
    return field;
}

TEST_F(InverseFft, TheGassRealFftIsAPlainDftAlongTheRowsOrBothAxesAndItsInverseUndoesIt) {
    // A random 24x10 field (a width VkFFT splits into radices 2 and 3): its transform is the plain
    // DFT's half spectrum to 1e-5 of the largest value, along the rows (RealFft::Rows, the gas
    // between walls) and along both axes (Both, on a torus); the inverse of that spectrum is the
    // field times W (Rows) or W H (Both). Bad buffers are refused by name.
    const std::vector<float> field = randomField(24, 10, 5);
    for (const RealFft::Axes axes : {RealFft::Axes::Rows, RealFft::Axes::Both}) {
        const bool both = axes == RealFft::Axes::Both;
        RealFft fft(cl(), 24, 10, axes);
        const auto [dft, roundTrip] = realFftErrors(cl(), fft, field);
        std::printf("[real fft] %s: %.2g of the largest value off the DFT; the inverse %.2g off the field\n",
                    both ? "both axes" : "rows", dft, roundTrip);
        EXPECT_LT(dft, 1e-5);
        EXPECT_LT(roundTrip, 1e-5);
        cl::Buffer in(cl().context(), CL_MEM_READ_WRITE, fft.fieldBytes());
        cl::Buffer spectrum(cl().context(), CL_MEM_READ_WRITE, fft.spectrumBytes());
        cl::Buffer small(cl().context(), CL_MEM_READ_WRITE, 64);
        EXPECT_NE(messageOf([&] { fft.forward(in, small); })
                      .find("RealFft: the spectrum holds 64 bytes, a 24x10 transform"),
                  std::string::npos);
        EXPECT_NE(messageOf([&] { fft.inverse(spectrum, small); }).find("RealFft: the field holds 64 bytes"),
                  std::string::npos);
    }
    EXPECT_NE(messageOf([&] { RealFft(cl(), 23, 10, RealFft::Axes::Rows); }).find("even width"), std::string::npos);
}

/// A locale whose numbers read "0,5": glibc's German one, compiled from Debian's locale sources
/// (the locales package, scripts/setup.sh) into the tests' output folder, as newlocale returns it;
/// 0 where it cannot be made.
locale_t commaLocale() {
    const std::string dir = outputPath("locales");
    std::filesystem::create_directories(dir);
    if (!std::filesystem::exists(dir + "/de_DE.UTF-8/LC_NUMERIC")) {
        // (localedef exits non-zero for warnings too: what it wrote is what counts.)
        const std::string command = "localedef -i de_DE -f UTF-8 '" + dir + "/de_DE.UTF-8' >/dev/null 2>&1";
        [[maybe_unused]] const int status = std::system(command.c_str());
    }
    setenv("LOCPATH", dir.c_str(), 1);
    const locale_t comma = newlocale(LC_ALL_MASK, "de_DE.UTF-8", locale_t(0));
    unsetenv("LOCPATH");
    return comma;
}

TEST_F(InverseFft, APlanMadeOnAThreadInItsOwnCommaLocaleBuildsAndLeavesThatLocale) {
    // A host thread may run in a locale of its own (uselocale), which a process-wide
    // setlocale("C") does not reach. VkFFT's generator, which set one around its sprintf, wrote
    // the constants of a radix-3 or radix-5 pass as "8,66...e-01" there, which C reads as its
    // comma operator: the gas's 24x10 pressure transform (both axes) came out 34x its largest
    // value off the DFT, with no error. The plan now runs this thread alone in the C locale and
    // gives it back its own. (The ocean's powers of two read their twiddles from a table on
    // PoCL and wrote no number; a GPU's plan may compute them.)
    const locale_t comma = commaLocale();
    ASSERT_TRUE(comma) << "localedef could not make de_DE.UTF-8 (Debian's locales package: scripts/setup.sh)";
    const std::vector<float> field = randomField(24, 10, 9);
    const locale_t before = uselocale(comma);
    char probe[16];
    std::snprintf(probe, sizeof probe, "%.1f", 0.5);
    std::pair<double, double> errors{1.0, 1.0};
    const std::string error = messageOf([&] {
        RealFft fft(cl(), 24, 10, RealFft::Axes::Both);
        errors = realFftErrors(cl(), fft, field);
    });
    const locale_t after = uselocale(before);
    freelocale(comma);
    EXPECT_STREQ(probe, "0,5") << "the locale writes no comma: the test cannot tell";
    EXPECT_EQ(after, comma) << "the plan did not give the thread back its locale";
    EXPECT_EQ(error, "(no error)");
    EXPECT_LT(errors.first, 1e-5);
    EXPECT_LT(errors.second, 1e-5);
}

} // namespace
} // namespace hfx::test
