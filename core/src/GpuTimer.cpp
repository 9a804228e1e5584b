#include "hfx/core/GpuTimer.h"

#include "hfx/core/Error.h"
#include "hfx/core/GlRenderer.h"

#include <algorithm>
#include <chrono>
#include <cstddef>

namespace hfx {
namespace {
thread_local GpuTimer* activeTimer = nullptr;
} // namespace

GpuTimer::GpuTimer() : softwareRasteriser_(glWorkarounds(currentGlRenderer()).cpuClockTimer) {
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits_);
}

GpuTimer::~GpuTimer() {
    if (running_ && !softwareRasteriser_) glEndQuery(GL_TIME_ELAPSED);
    if (!all_.empty()) glDeleteQueries(GLsizei(all_.size()), all_.data());
}

GLuint GpuTimer::query() {
    if (!spare_.empty()) {
        const GLuint q = spare_.back();
        spare_.pop_back();
        return q;
    }
    GLuint q = 0;
    glGenQueries(1, &q);
    all_.push_back(q);
    return q;
}

bool GpuTimer::ready(const Frame& frame) const {
    // Queries complete in order: the frame's last one done means all of them are.
    if (frame.segments.empty() || !frame.segments.back().query) return true;
    GLint available = 0;
    glGetQueryObjectiv(frame.segments.back().query, GL_QUERY_RESULT_AVAILABLE, &available);
    return available != 0;
}

void GpuTimer::read(Frame& frame) {
    std::map<std::string, double, std::less<>> sums;
    for (const std::string& name : frame.ran) sums[name]; // a pass that ran counts, if only as 0
    for (const Segment& segment : frame.segments) {
        double ms = segment.cpuMs;
        if (segment.query) {
            GLuint64 ns = 0;
            glGetQueryObjectui64v(segment.query, GL_QUERY_RESULT, &ns);
            ms = double(ns) * 1e-6;
            spare_.push_back(segment.query);
        }
        for (const std::string& name : segment.passes) sums[name] += ms;
    }
    for (const auto& [name, ms] : sums) samples_[name].push_back(ms);
    frame.segments.clear();
    frame.ran.clear();
}

double GpuTimer::nowMs() {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void GpuTimer::closeSegment() {
    if (!running_) return;
    if (softwareRasteriser_) {
        glFinish(); // the rasteriser's threads are the device (see GpuTimer.h)
        inFlight_.back().segments.back().cpuMs = nowMs() - segmentStart_;
    } else {
        glEndQuery(GL_TIME_ELAPSED);
    }
    running_ = false;
}

void GpuTimer::openSegment() {
    if (openPasses_.empty() || !available()) return;
    Segment segment;
    // Each pass counts once per segment, however often it is open (a pass inside itself).
    for (const auto& [handle, name] : openPasses_)
        if (std::find(segment.passes.begin(), segment.passes.end(), name) == segment.passes.end())
            segment.passes.push_back(name);
    if (softwareRasteriser_) {
        glFinish();
        segmentStart_ = nowMs();
    } else {
        segment.query = query();
        glBeginQuery(GL_TIME_ELAPSED, segment.query);
    }
    running_ = true;
    inFlight_.back().segments.push_back(std::move(segment));
}

void GpuTimer::beginFrame() {
    if (open_) endFrame();
    // Frames finish in order: read the done ones from the oldest, stop at the first that is not.
    size_t done = 0;
    while (done < inFlight_.size() && ready(inFlight_[done])) read(inFlight_[done++]);
    inFlight_.erase(inFlight_.begin(), inFlight_.begin() + std::ptrdiff_t(done));
    inFlight_.emplace_back();
    open_ = true;
}

void GpuTimer::endFrame() {
    // A pass still open at the frame's end is cut there (its scope's end() then finds it gone).
    closeSegment();
    openPasses_.clear();
    open_ = false;
}

int GpuTimer::begin(std::string_view name) {
    if (!open_) beginFrame();
    closeSegment();
    const int handle = nextHandle_++;
    openPasses_.emplace_back(handle, std::string(name));
    inFlight_.back().ran.emplace_back(name);
    openSegment();
    return handle;
}

void GpuTimer::end(int handle) {
    const auto it = std::find_if(openPasses_.begin(), openPasses_.end(),
                                 [&](const auto& pass) { return pass.first == handle; });
    if (it == openPasses_.end()) return; // cut by endFrame()
    closeSegment();
    openPasses_.erase(it);
    openSegment();
}

void GpuTimer::finish() {
    if (open_) endFrame();
    for (Frame& frame : inFlight_) read(frame); // GL_QUERY_RESULT waits for each
    inFlight_.clear();
}

GpuTimer::Activation::Activation(GpuTimer& timer) : previous_(activeTimer) { activeTimer = &timer; }
GpuTimer::Activation::~Activation() { activeTimer = previous_; }

GpuTimer* GpuTimer::active() { return activeTimer; }

} // namespace hfx
