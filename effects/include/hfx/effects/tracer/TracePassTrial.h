#pragma once
// Where the exact tracer walks a draw's rays (TracePass), and how TracePass::Auto picks the side on
// a device that no workaround decides for: it times both on the device's first draws and keeps the
// faster, as FFTW_MEASURE times an FFT's plans before it keeps one. Which side is faster depends on
// the device, not on the view: a graphics GPU runs fragments and compute on the same cores, where
// the compute pass adds its buffers (and on a sphere its rays draw); a compute chip (an H100, an
// H200) gives graphics a few of its cores and compute all of them; llvmpipe's compute stage is
// slower than its fragment stage (GlWorkarounds::traceInDraw decides there, measured).
//
// ExactTracer keeps a trial per mesh for camera views and one for shadow casters (a renderer that
// drew two meshes a frame under one trial would give one of them every turn of each side); this
// class holds a trial's decision from the times it is given (no GL).

#include <vector>

namespace hfx {

/// Where a hier draw walks its rays (DrawOptions::tracePass).
enum class TracePass {
    /// The device's: InDraw where GlWorkarounds::traceInDraw says so; elsewhere the faster of
    /// InDraw and Compute on this device, timed on the renderer's first such draws of each mesh
    /// (camera views and shadow casters apart: TracePassTrial, ExactTracer::passTrial).
    Auto,
    InDraw, ///< the surface draw's fragments walk their view and light rays
    /// Where it holds (a camera's or a shadow caster's draw of a convex mesh, Mesh::convex: a
    /// flat patch, a sphere; ExactTracer::prepare), a rays draw stores each pixel's view ray (and
    /// its light ray where that is not one for the draw; on a flat patch the pass finds the rays
    /// from the screen instead), a compute pass walks them a lane per pixel, and the shading draw
    /// reads the hit (trace/hier/trace.glsl): the same hits, walked on every core a compute
    /// dispatch reaches. Elsewhere InDraw.
    Compute,
};

/// "auto", "in the draw", "compute pass", for reports.
const char* tracePassName(TracePass pass);

/// Where a trial stands: the median time of each side's counted draws so far, and the decision.
struct TracePassTrialReport {
    TracePass chosen = TracePass::Auto; ///< InDraw or Compute once decided; Auto while trying
    double inDrawMs = 0.0;              ///< the median of InDraw's counted draws (0: none yet)
    double computeMs = 0.0;             ///< ... of Compute's
    int inDrawDraws = 0;                ///< InDraw's draws counted (after the warm-up)
    int computeDraws = 0;               ///< ... Compute's
    bool decided() const { return chosen != TracePass::Auto; }
};

class TracePassTrial {
public:
    /// Each side's first draws are not counted: they compile its programs (a GPU waits for them
    /// between its timestamps).
    static constexpr int kWarmUp = 1;
    /// Each side's counted draws whose medians decide: a trial of 8 draws ends within a bench's
    /// 10 warm-up frames (tools/include/hfx/tools/Timing.h), and one draw slowed by a neighbour
    /// or a compile does not move a median of three.
    static constexpr int kCounted = 3;
    /// The compute pass keeps a slot per pixel (24-32 bytes) and three passes: it is chosen only
    /// where its median is below this fraction of the draw's.
    static constexpr double kComputeMargin = 0.95;

    /// The side the next draw takes: the decided one, else the one that has begun fewer timed
    /// draws (Compute on a tie).
    TracePass next() const;
    /// A timed draw of `pass` began (its time comes later, in the order the draws began).
    void began(TracePass pass);
    /// A timed draw's time, in milliseconds, in the order `pass`'s draws began. A time that is
    /// not finite or below 0 (a timestamp that wrapped) is not counted, and another draw is timed.
    void record(TracePass pass, double ms);
    bool decided() const { return report_.decided(); }
    /// Whether a timed draw has begun.
    bool started() const { return inDraw_.begun > 0 || compute_.begun > 0; }
    /// Kept as the times come (no work per call: the demo reads it every frame).
    const TracePassTrialReport& report() const { return report_; }

private:
    struct Side {
        int begun = 0;     ///< timed draws begun
        int recorded = 0;  ///< times given, counted or not
        std::vector<double> counted;
    };
    Side& side(TracePass pass) { return pass == TracePass::Compute ? compute_ : inDraw_; }
    Side inDraw_, compute_;
    TracePassTrialReport report_;
};

} // namespace hfx
