#pragma once
// How right a surface technique is, per pixel: renders a height field on a plane with the
// technique's trace output (hit texcoords, depth fraction, fetch count, self-shadow) and
// compares every pixel with the exact intersection of the bilinear surface (HeightFieldTracer,
// double precision) and with exact shadow rays towards the light. The numbers of docs/ACCURACY.md
// and of the accuracy tests come from here.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/StaticField.h"
#include "hfx/core/HeightFieldTracer.h"
#include "hfx/core/Image.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/RenderTarget.h"
#include "hfx/effects/SurfacePipeline.h"
#include "hfx/effects/SurfaceRenderer.h"
#include "hfx/effects/tracer/BoundsPass.h"
#include "hfx/effects/tracer/TexelShadowPass.h"
#include "hfx/tools/Timing.h"

#include <limits>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace hfx {

/// The pass hier walks in where TracePass::Auto has decided on this device (the current GL
/// context's), with no trial: the draw where GlWorkarounds::traceInDraw (a CPU rasteriser), else the
/// compute pass, what the trial keeps on a GPU. Auto's trial takes the two by turns on a renderer's
/// first draws, and on a GPU they walk rays that differ by a rounding (its rasteriser's
/// interpolation; the compute pass's map of the screen), enough to move a hit at a grazing angle:
/// what compares two draws of one renderer (AccuracyProbe's Auto, the tests) names its pass.
TracePass deviceTracePass();

/// The accuracy renders' camera: looking at the origin from `angleDegrees` off +Y (the plane's
/// normal), `distance` away, a narrow field of view.
Camera accuracyCamera(double angleDegrees, float distance = 8.0f, float aspect = 1.0f);

/// The ray of pixel (x, y) (from the bottom-left) on a makePlane of edge `planeSize` (texcoords
/// 0..1): its entry texcoords and its texture-space vector towards the eye, or false when the ray
/// misses the plane.
bool planePixelRay(const Camera& camera, float planeSize, int x, int y, int width, int height, glm::dvec2& uv0,
                   glm::dvec3& toEye);
/// The same through the point (px, py) of the image, in pixels from its bottom-left corner (a
/// pixel's centre is x + 0.5).
bool planePointRay(const Camera& camera, float planeSize, double px, double py, int width, int height, glm::dvec2& uv0,
                   glm::dvec3& toEye);

/// A GPU rasteriser interpolates a fragment's inputs on a fixed-point grid of the pixel (GL asks
/// for at least 4 subpixel bits; NVIDIA and llvmpipe use 8): the ray a fragment traces is the
/// ray through a point within about this many pixels of its centre, not the centre's own. At
/// grazing views a neighbouring ray can pass a peak the centre's ray touches (a jump of the exact
/// hit by many texels), so the tracers' exactness is stated against the ray the fragment traced
/// (its entry texcoords, read back) and the rays this far around the centre's.
constexpr double kSubpixelTolerance = 1.0 / 256.0;

struct AccuracyConfig {
    double angleDegrees = 45.0;  ///< view angle from the plane's normal
    int image = 192;             ///< square render, pixels per edge
    float depthScale = 0.1f;     ///< texture widths (the plane spans one texture)
    int minSamples = 8, maxSamples = 32;
    bool shadows = false;        ///< compare the self-shadow with exact shadow rays
    glm::vec3 light{0.6f, 0.55f, 0.3f}; ///< world direction towards the light (plane normal +Y)
    float shadowSharpness = 2.0f; ///< the material's: its penumbra is where the clearance ratio < 1 / this
    float pixelBudget = 0.0f;     ///< the material's: the tracers' screen budget, pixels (0: full effort)
    /// With shadows: hier reads the texel shadows of the light (DrawOptions::texelShadows On;
    /// otherwise Off, whether or not they would pay) and walks only where the hard shadow
    /// changes between the samples.
    bool texelShadows = false;
    /// Their stride (DrawOptions::texelStride): every texelStride-th sample on each axis.
    int texelStride = 1;
    /// The exact tracer's beam start (DrawOptions::beamStart; the probe's planes are flat patches).
    bool beamStart = true;
    /// With texelShadows: the light walks they leave go to the pass after the draw
    /// (DrawOptions::deferShadowWalks; never where the draw writes its trace output).
    bool deferShadowWalks = false;
    /// Where hier walks its rays (DrawOptions::tracePass). Auto: deviceTracePass(), or the draw
    /// with deferShadowWalks (the draw's): every measure() of a probe walks in one pass.
    TracePass tracePass = TracePass::Auto;
    /// measure()'s camera distance from the plane's centre, world units (the plane is 2 wide);
    /// 0: the default, 8, from where the whole plane is seen.
    float cameraDistance = 0.0f;
    /// Shadow comparison skips points whose exact shadow changes within this many texels (the
    /// texel the boundary falls in, where a hit a little off flips it), and points in the
    /// penumbra band: the light ray is clear, but the cone edge (the ray lowered by
    /// 1 / shadowSharpness of its climb, from a texel away) is not.
    double penumbraTexels = 1.5;
    /// measure() draws its image moved by this many pixels (Camera::jitter) and compares with the
    /// rays through the unmoved pixels' centres (over4CentreRay) and the fragments' own: a
    /// rasteriser rounding the fragments' inputs, made on purpose (tests of the measure).
    glm::dvec2 jitterPixels{0.0, 0.0};
};

/// Height and bound fetches per drawn pixel, the view's and the light walk's together: the mean,
/// and per pixel when the pixels of each 4x2 block (llvmpipe's 8 lanes) or 8x4 block (a 32-lane
/// GPU warp) run in lockstep, each as long as its block's longest.
///
/// And what a cap on the walks would leave a 32-lane GPU: each pixel stops after `cap` fetches in
/// the draw (its 8x4 block as long as its longest capped pixel), and a compute pass finishes the
/// pixels it stopped, 32 to a warp in screen order, each as long as its warp's longest rest plus
/// kStragglerRestart fetches for taking up the walk again (its setup, its state written and read).
/// `cap` is the one of kStragglerCaps that leaves the fewest; 0 where no cap leaves fewer than
/// none (lanes32Capped is then lanes32).
struct FetchCounts {
    double mean = 0, lanes8 = 0, lanes32 = 0;
    double lanes32Capped = 0;
    int cap = 0;
};
inline constexpr int kStragglerCaps[] = {4, 6, 8, 12, 16, 24, 32, 48, 64};
inline constexpr double kStragglerRestart = 3.0;

/// The fetches per drawn pixel of a trace image (w: the fetches in its integer part, 0 where
/// nothing was drawn) when the pixels of each blockWidth x blockHeight block (from the image's
/// corner) run in lockstep, each as long as its block's longest: a loop on a SIMD machine runs
/// until its last lane is done. With a cap, each pixel stops after `cap` fetches, and a pass
/// finishes the pixels stopped, a block's worth of lanes at a time in screen order, each as long as
/// its group's longest rest plus `restart` (FetchCounts::lanes32Capped).
double lockstepFetches(const std::vector<glm::vec4>& trace, int width, int height, int blockWidth, int blockHeight,
                       int cap = std::numeric_limits<int>::max(), double restart = 0.0);

struct AccuracyResult {
    size_t pixels = 0;              ///< pixels on the plane compared
    double mean = 0, p95 = 0, max = 0; ///< texcoord error in texels
    double over4 = 0;               ///< fraction of pixels more than 4 texels off
    /// The same against the ray through the pixel's centre alone (the other figures take the
    /// fragment's own ray: see measure()).
    double over4CentreRay = 0;
    /// The same error on the screen: the traced and the exact point on the relief, both projected,
    /// in pixels of the measured image (mean, 95th percentile, fraction more than a pixel off).
    double meanPixels = 0, p95Pixels = 0, overPixel = 0;
    double depthMean = 0;           ///< |depth fraction - exact| (what gl_FragDepth is made of)
    double fetches = 0;             ///< mean height fetches per pixel, counted in the shader
    /// The same per drawn pixel when each block of pixels runs in lockstep and pays for its
    /// longest lane: 4x2 blocks (llvmpipe's 256-bit vectors: two 2x2 quads) and 8x4 blocks (a
    /// 32-lane GPU warp). Over `fetches`, what divergence costs a SIMD machine (`fetches`
    /// averages the compared pixels, these every drawn one: the few at the plane's edge differ).
    double fetchesLanes8 = 0, fetchesLanes32 = 0;
    double shadowAgreement = 1.0;   ///< fraction of compared points whose shadow state agrees
    size_t shadowPixels = 0;        ///< points compared for the shadow (outside the penumbra band)
    size_t penumbraPixels = 0;      ///< points left out as in the penumbra band
};

class AccuracyProbe {
public:
    /// heights: size x size in [0,1], row 0 at v = 0, tiling (edges wrap); size a power of two.
    /// The surface is made by the frames' own path (a StaticField down a SurfacePipeline:
    /// normals for `normalDepth`, packing, transfer), so the figures are those of what the
    /// effects draw; measure() may draw any depth. format: the surface's storage (to measure what
    /// a smaller format costs); unorm8 takes no height bounds, so it cannot measure the
    /// hierarchical technique. layout: how the tracer holds its bounds (DrawOptions::boundsLayout).
    AccuracyProbe(ClContext& cl, std::vector<float> heights, int size, float normalDepth,
                  SurfaceFormat format = SurfaceFormat::Float32, PyramidLayout layout = PyramidLayout::Auto);

    /// Renders the technique and compares every pixel's hit with the exact one. A pixel's error is
    /// against the exact hit of the ray the fragment traced (from the entry texcoords the
    /// rasteriser gave it, towards the eye) or, where that one is more than a texel or half a
    /// pixel off, of the ray through its centre or through any of 8 points kSubpixelTolerance
    /// around it, whichever is nearest: which ray a fragment traces is the rasteriser's rounding,
    /// not the tracer's (over4CentreRay keeps the centre's alone).
    AccuracyResult measure(Technique technique, const AccuracyConfig& config);
    /// Median milliseconds of `repeats` draws of the technique filling a width x height target at
    /// config's angle (the plane fills the view), after `warmups` draws not counted: GPU time
    /// (timer queries around the clear and the draw, its beam start and cells included) and the
    /// wall clock around glFinish.
    /// The rays of timeDraw's view (its camera through every pixel centre that meets the plane),
    /// traced in a compute shader over these textures with the renderer's accessors
    /// (surface/heights.glsl), each view ray then its soft shadow to config's light, one
    /// invocation a ray: the tracer without the rasteriser, on every compute unit of the device
    /// (a compute chip runs fragment shaders on a few). No texel shadows or beam start: the walk
    /// itself. One dispatch, both clocks. Also returns, with `fetches`, the
    /// mean height and bound fetches a ray made.
    GlTime timeCompute(Technique technique, const AccuracyConfig& config, int width, int height,
                       double* fetches = nullptr);
    GlTime timeDraw(Technique technique, const AccuracyConfig& config, int width, int height, int repeats,
                    int warmups = 1);
    /// The height and bound fetches per pixel of that same draw (timeDraw's view and size),
    /// counted in the shader: what the timed pixels fetch, which measure()'s far view does not show.
    FetchCounts countFetches(Technique technique, const AccuracyConfig& config, int width, int height);
    /// Median milliseconds of the texel shadows' pass for config's light at config's stride, as
    /// the exact tracer runs it after new heights (their pyramid's build included), on both
    /// clocks; 0 without shadows.
    GlTime timeTexelShadows(const AccuracyConfig& config, int repeats);
    /// The light walks the last timeDraw() that deferred them left to the pass after the draw
    /// (ExactTracer::deferredWalks: past the buffer's capacity, walked in the draw).
    int deferredWalks() const;
    /// The colour image of the last timeDraw() (top row first).
    const Image& lastFrame() const { return lastFrame_; }
    /// GPU milliseconds of each pass the last timeDraw() ran, by the name of its GpuScope ("rays",
    /// "walks" and "draw" of the compute pass, "beam", "draw total" around them all): the median of
    /// its counted draws.
    const std::map<std::string, double, std::less<>>& lastPasses() const { return lastPasses_; }
    const HeightFieldTracer& exact() const { return exact_; }
    const SurfaceTextures& textures() const { return surface_.textures(); }

private:
    /// config's light as the exact tracer's shadow rays see it on the probe's plane; empty
    /// without shadows or a pyramid.
    std::optional<ShadowLight> shadowLight(const AccuracyConfig& config) const;
    DrawOptions drawOptions(Technique technique, const AccuracyConfig& config, bool traceOutput) const;

    int size_;
    HeightFieldTracer exact_;
    StaticField field_;
    SurfacePipeline surface_;
    SurfaceRenderer renderer_;
    std::unique_ptr<RenderTarget> target_;      ///< measure()'s, with the trace output
    std::unique_ptr<RenderTarget> timedTarget_; ///< timeDraw()'s
    Image lastFrame_;
    std::map<std::string, double, std::less<>> lastPasses_;
    Mesh plane_, timedPlane_;
    TexelShadowPass texelPass_; ///< timeTexelShadows' pass, and what it draws into
    TexelShadows texels_;
    GpuTimer timer_;
    // timeCompute's rays (for the view and size they were made for) and programs.
    std::tuple<double, int, int, float> computeKey_{};
    int computeRays_ = 0;
    GlBuffer computeIn_, computeOut_, computeBlock_;
    std::map<std::tuple<Technique, bool, bool>, ShaderProgram> computePrograms_; ///< by technique, atlas, bounded search
    PyramidLayout layout_; ///< resolved
    TracePass devicePass_; ///< deviceTracePass(), asked once: drawOptions runs inside the timed draws
    /// The texel-shadow pass's and the compute harness's bounds of the surface, made on first use
    /// (the renderer's tracer holds its own)
    HeightBounds& bounds();
    std::unique_ptr<HeightBounds> bounds_;
    BoundsPass boundsPass_;
};

} // namespace hfx
