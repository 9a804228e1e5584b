#pragma once
// What the compute side may know of the caller's GL context: who renders it (to put the compute
// device on the same hardware) and, for cl_khr_gl_sharing, its native handles. Plain data, so
// that compute never asks GL for it behind the caller's back.
//
// Thread: currentGlRenderer() on the thread whose context is current; the rest any.

#include <string>

namespace hfx {

/// glGetString(GL_VENDOR) and glGetString(GL_RENDERER); empty when not known.
struct GlRendererInfo {
    std::string vendor;
    std::string renderer;
    bool empty() const { return vendor.empty() && renderer.empty(); }
    /// A CPU rasteriser (llvmpipe, softpipe, swrast, SwiftShader, Microsoft's basic renderer).
    bool software() const;
};

/// The renderer of the current context.
GlRendererInfo currentGlRenderer();

/// Where HFX does, on a CPU rasteriser, what a GPU would not want: each switch measured to pay
/// there (docs/BENCHMARKS.md), and all of them here, detected from the renderer. Everywhere else
/// the code is written for a GPU. HFX_GL_WORKAROUNDS overrides them, "name=0|1" separated by
/// commas (cpu-clock-timer, float32-surfaces, pyramid-atlas, pyramid-from-compute, trace-in-draw),
/// so either side runs on any device: tests hold the two sides to the same results, benches time
/// one against the other.
struct GlWorkarounds {
    /// GpuTimer: the CPU clock between two glFinish times a pass. A CPU rasteriser has no device
    /// clock: its timer queries stamp one tile of a pass, a fraction of the work.
    bool cpuClockTimer = false;
    /// SurfacePipeline (effects): SurfaceFormat::Auto stores a surface as float32 (RGBA32F), not
    /// float16. llvmpipe converts an RGBA16F texel on every fetch (the water's POM draw 1.09-1.22x
    /// float32's) and a float16 surface's bounds are built by GL, not the compute device
    /// (pyramidFromCompute: 1.6-1.9x), for a transfer of 0.70-1.01x: frames 0.98-1.07x. A GPU
    /// moves and samples half the bytes: on an H100 float16 took the water's transfer to
    /// 0.65-0.81x and its POM draw to 0.67x float32's (docs/BENCHMARKS.md).
    bool float32Surfaces = false;
    /// HeightBounds (effects): the bounds pyramid as one RG32F image read with imageLoad, and the level-0
    /// cells' samples as an RGBA32F image (BoundsPass), instead of a mip chain read with
    /// texelFetch at the lane's level and a textureGather of the heights. On llvmpipe a texelFetch
    /// with a level per lane is a call that spills the walk's vectors (1.6x an imageLoad) and a
    /// gather costs 2.2x an RGBA32F imageLoad; on a GPU each is one texture instruction.
    bool pyramidAtlas = false;
    /// SurfacePipeline (effects): a float32 surface's bounds pyramid built on the compute device
    /// from the heights and uploaded with the texels while draws read them (as
    /// HeightBounds::upload takes it, SurfacePipeline::bounds), instead of built by GL from the stored texels (BoundsPass). On llvmpipe beside PoCL, GL's build
    /// (four texelFetch calls a cell) cost 10-11 ms more than PoCL's and the copy at 512² and
    /// 54 ms at 1024² (the decal wall's hier draw), 34-106 ms a frame for the ocean's four
    /// cascades; on a GPU the build is one small pass and saves moving 10.7 bytes a texel.
    bool pyramidFromCompute = false;
    /// ExactTracer (effects): TracePass::Auto walks hier's view and light rays in the surface
    /// draw's fragment stage, with no trial of the compute pass (a rays draw, a dispatch that
    /// walks them a lane per pixel, the shading draw: TracePass::Compute). Elsewhere Auto times
    /// both on the first draws and keeps the faster (TracePassTrial): a GPU may give graphics a
    /// few of its cores and compute all of them (an H200 traced the same rays in 0.07-0.25 ms in
    /// a compute pass against 2.8-7.0 ms in hier's draw), or all of them to both. llvmpipe runs
    /// both on the same threads, its compute stage slower: the three passes cost 1.3-1.75x the
    /// draw that walks (docs/BENCHMARKS.md), and the trial, run there with this off, keeps the
    /// draw; this saves its eight draws' glFinish and their frames' changes of pass.
    bool traceInDraw = false;
};

/// The workarounds for `renderer`, HFX_GL_WORKAROUNDS applied; throws hfx::Error naming a bad
/// entry and the valid names.
GlWorkarounds glWorkarounds(const GlRendererInfo& renderer);

/// A GL context's native handles, as cl_khr_gl_sharing takes them (CL_GL_CONTEXT_KHR with
/// CL_GLX_DISPLAY_KHR or CL_EGL_DISPLAY_KHR). None: the context cannot be shared (OSMesa).
struct GlShareHandles {
    enum class Api { None, Glx, Egl };
    Api api = Api::None;
    void* context = nullptr; ///< GLXContext or EGLContext
    void* display = nullptr; ///< X11 Display* or EGLDisplay
};

} // namespace hfx
