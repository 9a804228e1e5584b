#pragma once
// Timing for the benchmarks (the demo's and the accuracy probe's). Two clocks for every figure:
// - GPU time: GL_TIMESTAMP queries around the work (GpuTimer), what the device spent on it, pass
//   by pass (and CL event profiling for kernels: ClContext::recordKernelTimes);
// - wall: the CPU clock around the work with the GL queue drained before and after (glFinish),
//   which adds the submit-and-sync cost a frame pays on the CPU side.
// Medians of interleaved runs after warm-up: this machine is shared and noisy, a GPU boosts its
// clocks, and the first frames build shaders and fill caches.

#include "hfx/core/Gl.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/core/Median.h"

#include <algorithm>
#include <chrono>
#include <vector>

namespace hfx {

/// Frames every bench runs and throws away before it measures (shader builds, caches, clocks).
constexpr int kWarmupFrames = 10;
/// Frames (or interleaved rounds) every bench takes the median of, at the least.
constexpr int kTimedFrames = 30;

/// Milliseconds of f() with the GL queue drained before and after.
template <typename F>
double timeMs(F&& f) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    f();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// One measurement of GL work on both clocks, milliseconds.
struct GlTime {
    double gpu = 0.0;  ///< timestamps around it, on the device
    double wall = 0.0; ///< the CPU clock around it, glFinish before and after
};

/// Times f() on both clocks: `timer` records it as the pass `name` in a frame of its own (read at
/// once: the wall clock's glFinish has drained the queue), the wall clock around glFinish.
template <typename F>
GlTime timeGl(GpuTimer& timer, const char* name, F&& f) {
    GpuTimer::Activation on(timer);
    glFinish(); // an idle GPU: the first timestamp is taken when f's work can start
    timer.beginFrame();
    const auto start = std::chrono::steady_clock::now();
    {
        const GpuScope scope(name);
        f();
    }
    glFinish();
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    timer.endFrame();
    timer.finish();
    const auto it = timer.samples().find(name);
    const double gpu = it == timer.samples().end() || it->second.empty() ? 0.0 : it->second.back();
    return {gpu, wall};
}

/// The medians of a series of measurements, clock by clock.
inline GlTime median(const std::vector<GlTime>& times) {
    std::vector<double> gpu, wall;
    for (const GlTime& t : times) {
        gpu.push_back(t.gpu);
        wall.push_back(t.wall);
    }
    return {median(gpu), median(wall)};
}

} // namespace hfx
