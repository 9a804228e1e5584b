#pragma once
// A batched 2D inverse real FFT on the OpenCL device, through VkFFT's OpenCL back end (MIT,
// header-only; Debian: libvkfft-dev): `batch` Hermitian half spectra to N x N real fields.
//
//   field(x, y) = sum over kx, ky of S(kx, ky) e^{+2 pi i (kx x + ky y) / N}
//
// unscaled (a field is the plain sum of its modes), with S given on the half plane kx = 0..N/2:
// rows of N/2 + 1 complex values (float2), N rows (ky = 0..N-1), one spectrum after another; the
// fields come out as N x N floats, one after another. VkFFT generates and builds its kernels
// when the plan is made, so no frame pays for compiling them. The spectrum buffer is the
// transform's scratch: it holds garbage afterwards.
//
// Owns the VkFFT plan. Thread: the thread that owns the ClContext. Making one sets the process's
// locale to "C" while VkFFT plans, and puts the caller's back (VkFFT's own save and restore reads
// freed memory under a composite locale).

#include "hfx/compute/ClContext.h"

#include <cstddef>
#include <memory>
#include <string>

namespace hfx {

class InverseRealFft {
public:
    /// Plans for N x N (a power of two, 2..8192) fields, `batch` of them (1..64). Throws
    /// hfx::Error naming the size and the device when VkFFT cannot make the plan (its kernels'
    /// build log goes to stdout, where VkFFT prints it).
    InverseRealFft(ClContext& cl, int n, int batch);
    ~InverseRealFft();
    InverseRealFft(const InverseRealFft&) = delete;
    InverseRealFft& operator=(const InverseRealFft&) = delete;

    /// Enqueues the transforms of `spectrum` (spectrumBytes()) into `fields` (fieldBytes()) on
    /// the context's queue.
    void enqueue(const cl::Buffer& spectrum, const cl::Buffer& fields);

    int size() const { return n_; }
    int batch() const { return batch_; }
    size_t spectrumBytes() const { return size_t(batch_) * size_t(n_ / 2 + 1) * size_t(n_) * 2 * sizeof(float); }
    size_t fieldBytes() const { return size_t(batch_) * size_t(n_) * size_t(n_) * sizeof(float); }
    /// "VkFFT 1.2.26", for start-up reports.
    static std::string libraryVersion();

private:
    struct Plan;
    ClContext& cl_;
    int n_, batch_;
    std::unique_ptr<Plan> plan_;
};

} // namespace hfx
