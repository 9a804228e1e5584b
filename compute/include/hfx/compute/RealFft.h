#pragma once
// A forward and inverse real FFT of a W x H field on the OpenCL device, through VkFFT's OpenCL
// back end (as InverseRealFft): along each row alone, or along both axes.
//
//   forward:  S(k, l) = sum over x, y of f(x, y) e^{-2 pi i (k x / W + l y / H)}   (Both)
//             S(k, y) = sum over x of f(x, y) e^{-2 pi i k x / W}                  (Rows)
//   inverse:  the same sums with e^{+...}, unscaled: inverse(forward(f)) = W f (Rows), W H f (Both)
//
// The field is W x H floats, row-major; the spectrum keeps the half rows k = 0..W/2: rows of
// W/2 + 1 complex values (float2), H of them (l = 0..H-1 for Both, y for Rows). The inverse uses
// the spectrum as its scratch: it holds garbage afterwards. VkFFT builds its kernels when the
// plan is made, so no step pays for compiling them.
//
// Owns the VkFFT plan. Thread: the thread that owns the ClContext.

#include "hfx/compute/ClContext.h"

#include <cstddef>
#include <memory>

namespace hfx {

class RealFft {
public:
    enum class Axes { Rows, Both };
    /// Plans for W x H fields (W even, both in [2, 8192]). Throws hfx::Error naming the size and
    /// the device when VkFFT cannot make the plan.
    RealFft(ClContext& cl, int width, int height, Axes axes);
    ~RealFft();
    RealFft(const RealFft&) = delete;
    RealFft& operator=(const RealFft&) = delete;

    /// Enqueues `field`'s transform (fieldBytes(), left as it is) into `spectrum` (spectrumBytes()).
    void forward(const cl::Buffer& field, const cl::Buffer& spectrum);
    /// Enqueues `spectrum`'s inverse transform into `field`.
    void inverse(const cl::Buffer& spectrum, const cl::Buffer& field);

    int width() const { return width_; }
    int height() const { return height_; }
    Axes axes() const { return axes_; }
    size_t spectrumBytes() const { return size_t(width_ / 2 + 1) * size_t(height_) * 2 * sizeof(float); }
    size_t fieldBytes() const { return size_t(width_) * size_t(height_) * sizeof(float); }

private:
    void enqueue(const cl::Buffer& spectrum, const cl::Buffer& field, int direction);
    struct Plan;
    ClContext& cl_;
    int width_, height_;
    Axes axes_;
    std::unique_ptr<Plan> plan_;
};

} // namespace hfx
