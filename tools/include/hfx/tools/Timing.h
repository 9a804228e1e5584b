#pragma once
// Timing for the benchmarks (the demo's and the accuracy probe's): GL work bracketed by glFinish,
// and medians (this machine is shared and noisy; medians of interleaved runs are what the
// benchmarks report).

#include "hfx/core/Gl.h"

#include <algorithm>
#include <chrono>
#include <vector>

namespace hfx {

inline double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

/// Milliseconds of f() with the GL queue drained before and after.
template <typename F>
double timeMs(F&& f) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    f();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace hfx
