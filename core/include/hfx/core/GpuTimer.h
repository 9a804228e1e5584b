#pragma once
// GPU time of named passes: GL_TIME_ELAPSED queries, read back once their frame is done (a frame
// or more later, so the frame never waits for them). What the GPU spent from a pass's first
// command to its last, without the submit-and-sync cost that a CPU clock around glFinish adds,
// and pass by pass where glFinish lumps them together.
//
// Passes nest ("whole" around "draw" around ...), but only one GL_TIME_ELAPSED query runs at a
// time: the open passes' span is cut into segments at every scope boundary, one query each,
// and a segment's time counts for every pass open across it.
//
// A CPU rasteriser (llvmpipe) has no device clock: its timer queries stamp each tile of a scene
// as its rasteriser threads reach it, so a GL_TIME_ELAPSED query measures about the last tile
// (a full-screen draw of 34 ms read 0.96 ms) and a GL_TIMESTAMP pair likewise. There, and only
// there, a segment is timed by the CPU clock between two glFinish: the rasteriser's threads are
// the device, and their work between the two is the pass's: the `softwareRasteriser_` switch,
// GlWorkarounds::cpuClockTimer (GlRenderer.h, where every such switch lives).
//
// The module's passes open a GpuScope named after themselves ("upload", "cells", "texel
// shadows", "beam", "draw", "shadow map"); a scope records on the timer active on this thread
// (GpuTimer::Activation), and costs one thread-local read when none is.
//
//   GpuTimer timer;
//   GpuTimer::Activation on(timer);
//   for (each frame) { timer.beginFrame(); ... passes ...; timer.endFrame(); }
//   timer.finish();                        // reads the frames still in flight
//   median(timer.samples().at("draw"));    // milliseconds, one per frame that drew
//
// Owns its query objects. Thread: the thread whose GL context is current.

#include "hfx/core/GlObject.h"

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hfx {

class GpuTimer {
public:
    GpuTimer();
    ~GpuTimer();
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    /// Starts a frame; first reads back every earlier frame whose queries are done.
    void beginFrame();
    /// Ends the frame begun last (its queries are read by a later beginFrame() or finish()).
    void endFrame();
    /// Opens a pass of the current frame (a frame of its own when none is begun). Returns a
    /// handle for end(). Passes may nest and repeat; a pass's time in a frame is the sum of its
    /// scopes there.
    int begin(std::string_view name);
    /// Closes the pass `handle` opened.
    void end(int handle);
    /// Waits for every frame in flight and reads it.
    void finish();

    /// Milliseconds of GPU time per pass name: one value per frame read back that ran the pass.
    const std::map<std::string, std::vector<double>, std::less<>>& samples() const { return samples_; }
    /// Forgets the samples (frames still in flight are read into the fresh ones).
    void clearSamples() { samples_.clear(); }
    /// Timer queries exist here (GL_QUERY_COUNTER_BITS of GL_TIME_ELAPSED > 0), or the renderer
    /// is a CPU rasteriser, timed by the CPU clock.
    bool available() const { return bits_ > 0 || softwareRasteriser_; }
    /// The passes are timed by the CPU clock around glFinish (a CPU rasteriser: see above).
    bool cpuClock() const { return softwareRasteriser_; }

    /// Makes `timer` the one GpuScopes on this thread record on, for its lifetime (the previous
    /// one comes back after).
    class Activation {
    public:
        explicit Activation(GpuTimer& timer);
        ~Activation();
        Activation(const Activation&) = delete;
        Activation& operator=(const Activation&) = delete;

    private:
        GpuTimer* previous_;
    };
    /// The timer GpuScopes record on, or null.
    static GpuTimer* active();

private:
    /// One GL_TIME_ELAPSED query (or, on a software rasteriser, its CPU-clock milliseconds) and
    /// the passes open across it.
    struct Segment {
        GLuint query = 0;
        double cpuMs = 0.0;
        std::vector<std::string> passes;
    };
    struct Frame {
        std::vector<Segment> segments;
        std::vector<std::string> ran; ///< every pass opened in the frame, even with no segment
    };
    GLuint query();
    bool ready(const Frame& frame) const;
    void read(Frame& frame);
    static double nowMs();
    void closeSegment(); ///< ends the running query, if any, for the passes open now
    void openSegment();  ///< starts a query for the passes open now, if any

    std::vector<Frame> inFlight_;
    bool open_ = false;
    std::vector<std::pair<int, std::string>> openPasses_; ///< handle and name, innermost last
    int nextHandle_ = 0;
    bool running_ = false; ///< a segment's query is running
    bool softwareRasteriser_ = false; ///< segments timed by the CPU clock (see the top of this file)
    double segmentStart_ = 0.0;       ///< ... since this many ms of std::chrono::steady_clock
    std::vector<GLuint> spare_; ///< query objects of frames read back, for reuse
    std::vector<GLuint> all_;   ///< every query object made, deleted by the destructor
    std::map<std::string, std::vector<double>, std::less<>> samples_;
    GLint bits_ = 0;
};

/// A pass on the active GpuTimer (see above), from construction to destruction.
class GpuScope {
public:
    explicit GpuScope(std::string_view name)
        : timer_(GpuTimer::active()), handle_(timer_ ? timer_->begin(name) : -1) {}
    ~GpuScope() {
        if (timer_) timer_->end(handle_);
    }
    GpuScope(const GpuScope&) = delete;
    GpuScope& operator=(const GpuScope&) = delete;

private:
    GpuTimer* timer_;
    int handle_;
};

} // namespace hfx
