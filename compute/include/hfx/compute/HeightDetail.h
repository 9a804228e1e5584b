#pragma once
// Noise put on a changing field: each run() writes base + amount (noise - 0.5), clamped to
// [0,1], the noise being an animated NoiseField of the field's size and edges (the gas giant's
// cloud tops get their fine relief from it), optionally faded to 0.5 within capRows of the
// first and last rows (a longitude-latitude map's poles). The noise steps with the field.
//
// Owns its noise, its output buffer and kernel. Thread: the thread that owns the ClContext.

#include "hfx/compute/NoiseField.h"

namespace hfx {

class HeightDetail {
public:
    /// noise: its size and edges are the field's; amount in [0, 1]; capRows in [0, rows / 2].
    HeightDetail(ClContext& cl, const NoiseConfig& noise, float amount, float capRows = 0.0f);

    /// Moves the noise on by dt seconds.
    void step(double dt) { noise_.step(dt); }
    /// Enqueues the detailed heights of `base` (width*height floats) into output().
    void run(const cl::Buffer& base);
    const cl::Buffer& output() const { return output_; }
    const NoiseField& noise() const { return noise_; }
    float amount() const { return amount_; }
    float capRows() const { return capRows_; }

private:
    ClContext& cl_;
    NoiseField noise_;
    float amount_, capRows_;
    cl::Buffer output_;
    cl::Kernel kernel_;
};

} // namespace hfx
