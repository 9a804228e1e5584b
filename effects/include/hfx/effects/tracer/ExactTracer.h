#pragma once
// The exact tracer's home (Technique::Hierarchical, shaders/trace/hier.glsl): what a hier draw
// needs besides the surface textures, made each frame from what the draw is given, and the
// policy that decides it. SurfaceRenderer owns one and calls prepare() before every hier draw and
// every bounded search; nothing outside decides anything per frame for it.
//
//   bounds      the height-bounds pyramid of every traced layer (HeightBounds), held here per
//               surface and built from the stored texels where they changed (BoundsPass; hier's
//               and the bounded searches'), or the layer's own where its producer built them
//               (SurfaceLayer::bounds)
//   texel       the exact self-shadow at every stride-th sample of the field (TexelShadowPass),
//   shadows     where they pay on this view: a flat patch showing more pixels than its samples
//               (texelShadowStride, with SurfaceMaterial::pixelBudget); kept per surface while
//               its texels and the light stay
//   beam start  a prepass walking one ray per block of kBeamBlock² pixels, where the view rays
//               start (DrawOptions::beamStart, a flat patch)
//   deferred    the light walks the texel shadows do not hold, left by the draw to a pass after
//   walks       it (finish, trace/hier/deferred.glsl): one walk to a lane, not one lane's walk
//               holding up its warp (DrawOptions::deferShadowWalks)
//   computed    for a convex mesh (a flat patch, a sphere; a caster's too): a rays draw
//   walks       stores each pixel's view ray (on a flat patch walks() finds it from the screen
//               instead: no rays draw), walks() walks it and its light ray a lane per pixel in a
//               compute pass, and the shading draw reads the hits (DrawOptions::tracePass,
//               trace/hier/trace.glsl); TracePass::Auto takes it where this device draws it
//               faster, timed on the first draws (TracePassTrial, passTrial)
//
// Thread: the thread whose GL context is current.

#include "hfx/core/GlFence.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/core/Mesh.h"
#include "hfx/core/ShaderProgram.h"
#include "hfx/core/ShadowLight.h"
#include "hfx/core/SurfaceTextures.h"
#include "hfx/effects/SurfaceUniforms.h"
#include "hfx/effects/tracer/BoundsPass.h"
#include "hfx/effects/tracer/TexelShadowPass.h"
#include "hfx/effects/tracer/TracePassTrial.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <utility>

namespace hfx {

struct DirectionalLight;
struct DrawOptions;
struct SurfaceMaterial;
struct SurfaceLayer;

/// Whether a hier draw reads texel shadows (DrawOptions::texelShadows).
enum class TexelShadowChoice {
    /// where they pay on the view, at the stride the policy picks (texelShadowStride), with the
    /// walks in the draw; off with the walks in a compute pass (TracerFrame::computeTrace)
    Auto,
    On,   ///< always on a flat patch: at DrawOptions::texelStride, else the policy's, else 1
    Off,  ///< never: every pixel walks its light ray
};

/// The light as the exact tracer's shadow rays see it on a flat mesh (Mesh::patch) drawn with
/// `model`: flatSurfaceLight of its frame. Empty for a mesh that is no flat patch, drawn with a
/// triplanar mapping (its frames are not the patch's), or where no shadow ray is traced. What the
/// renderer's texel shadows are drawn for.
std::optional<ShadowLight> flatPatchLight(const Mesh& mesh, const glm::mat4& model, const DirectionalLight& light,
                                          const SurfaceMaterial& material);

/// What ExactTracer::prepare decided for one draw: the surface program's variant follows it.
struct TracerFrame {
    bool boundedSearch = false; ///< a sampled search bounded by every traced layer's pyramid
    bool atlas = false;         ///< the bounds read are in PyramidLayout::Atlas
    const TexelShadows* texelShadows = nullptr; ///< hier's shadows read these where set
    int texelStride = 0;                        ///< their stride; 0: none read
    double pixelsPerTexel = 0.0;                ///< the flat patch's screen pixels per field texel (0: not flat)
    bool beamStart = false;                     ///< the beam prepass ran; its target is bound
    /// The draw appends the light rays its texel shadows do not hold (HFX_DEFERRED_SHADOWS), and
    /// finish() walks them and writes their pixels again; the buffer is bound.
    bool deferredShadows = false;
    /// The rays draw, walks() and the shading draw (TracePass::Compute): the buffers are bound and
    /// the uniform block's trace fields set.
    bool computeTrace = false;
    /// With computeTrace: the rays draw stores each pixel's light ray too (HFX_TRACE_LIGHTS), as
    /// the light is not the flat patch's one for the draw (a curved mesh, a silhouette fade).
    bool traceLights = false;
    /// With computeTrace, on a flat patch without a silhouette fade: walks() finds each pixel's
    /// ray from the screen (HFX_TRACE_PATCH: the patch's texcoords are a projective map of it, as
    /// a rasteriser interpolates them), and there is no rays draw. On a GPU that draws with a few
    /// of its cores a fragment pass has a cost no shader saving removes (docs/DESIGN.md).
    bool patchRays = false;
    /// With computeTrace: the planes of slots, a pixel's ray in each (trace/hier/trace.glsl): a
    /// triplanar mapping's three (each projection it weighs walks its own), else one.
    int tracePlanes = 1;
    /// One of TracePass::Auto's trial draws (TracePassTrial): prepare() began timing its passes
    /// (after its own), finish() ends it.
    bool timed = false;
};

/// The GL storage an ExactTracer holds, bytes: what an engine's memory budget counts (its
/// programs and uniform blocks aside).
struct TracerMemory {
    /// The compute pass's slots (TracePass::Compute): 24 bytes a pixel of the largest viewport it
    /// drew, 32 once a curved mesh's light rays were stored, three planes of them for a triplanar
    /// mapping; held while a trial may take the pass or it took it.
    size_t slots = 0;
    /// The height bounds of the surfaces drawn lately (up to eight; a producer's own,
    /// SurfaceLayer::bounds, are the producer's).
    size_t bounds = 0;
    size_t texelShadows = 0; ///< the texel shadows of the surfaces drawn lately (up to four)
    size_t prepasses = 0;    ///< the beam start's target and the deferred light walks' buffer
    size_t total() const { return slots + bounds + texelShadows + prepasses; }
};

class ExactTracer {
public:
    /// Makes and binds what a draw of `layers` reads besides their textures, as the view, the
    /// light and the material decide: the traced layers' bounds for hier and a bounded search
    /// (SurfaceMaterial::boundedSearch where every traced layer can carry them), and for hier the
    /// texel shadows (DrawOptions::texelShadows) and the beam start (DrawOptions::beamStart).
    /// `viewProj` is the camera's or, for a caster, the shadow map's (no texel shadows: a caster
    /// writes depth only). `u` is the draw's uniform block, filled but for the transform:
    /// prepare sets the texel shadows' light, and the beam prepass reads it. Changes texture
    /// and image units, the uniform-buffer binding and the current program: call it inside the
    /// renderer's GlStateGuard.
    TracerFrame prepare(std::span<const SurfaceLayer> layers, const Mesh& mesh, const glm::mat4& model,
                        const glm::mat4& viewProj, const DirectionalLight& light, const SurfaceMaterial& material,
                        const DrawOptions& options, bool caster, SurfaceUniforms& u);
    /// The last camera (not caster) hier draw's decision, for reports.
    const TracerFrame& last() const { return last_; }
    /// The last shadow caster's hier draw's decision (SurfaceRenderer::drawShadow).
    const TracerFrame& lastCaster() const { return lastCaster_; }
    /// Between the rays draw (none with TracerFrame::patchRays) and the shading draw of a frame
    /// with computeTrace, with the draw's textures, units and uniform block bound: walks every ray
    /// the rays draw stored, or the flat patch's pixels' rays, a lane per pixel
    /// (trace/hier/trace.comp). Changes the program: inside the renderer's GlStateGuard.
    void walks(const TracerFrame& frame);
    /// After every draw that prepare() was for, with its textures, units and uniform block still
    /// bound: where it deferred light walks (TracerFrame::deferredShadows), walks them one to a
    /// lane in a compute dispatch (trace/hier/deferred.comp) and writes their pixels again with
    /// a draw of points where the draw's depth still stands (deferred.vert); then ends a trial
    /// draw's timing (TracerFrame::timed). Changes the program, the vertex array, the indirect
    /// buffers and the depth function: inside the renderer's GlStateGuard.
    void finish(const TracerFrame& frame);
    /// Where TracePass::Auto stands on this device for `mesh`, seen by cameras or by shadow
    /// casters: the trial's times and, once its draws are timed, its choice (undecided with no
    /// draw timed where GlWorkarounds::traceInDraw decides, or no draw of it could take the
    /// compute pass). A trial per mesh (Mesh::uid): a renderer that draws two meshes a frame
    /// would otherwise give one of them every turn of each side. The trials of the kTrials meshes
    /// drawn last are held; a mesh drawn again after that is tried again.
    TracePassTrialReport passTrial(const Mesh& mesh, bool caster) const;
    static constexpr size_t kTrials = 256;
    /// How many light walks the last draw that deferred them appended (past the buffer's
    /// capacity, the rest were walked in the draw). Reads the buffer back: for tests and reports.
    int deferredWalks() const;
    /// How many rays the deferred walks' buffer holds: a ray per 16 pixels of the viewport, grown
    /// to what a draw appended once the GPU is past it (up to a ray per 4 pixels).
    int deferredCapacity() const { return deferredCapacity_; }
    /// The GL storage it holds now. Its buffers grow to the largest viewport drawn and its caches
    /// hold the surfaces drawn lately: release() lets go of all of it (after a screenshot at 4K,
    /// or a level's surfaces), and the next draws make what they need again (the bounds built
    /// from the stored heights, the texel shadows drawn); the trials' choices stay.
    TracerMemory memory() const;
    void release();

private:
    using Viewport = std::array<GLint, 4>; ///< x, y, width, height (GL_VIEWPORT)
    /// This context's workarounds (the bounds' layout, where the walks run), read at the first
    /// draw: a tracer lives in one context, and parsing them per draw cost two glGetString calls
    /// and the environment's each time.
    const GlWorkarounds& workarounds();
    /// The bounds of `layer`'s textures in `layout`: the layer's own where they hold its current
    /// texels, else the ones held here (made for a new surface, not yet built).
    HeightBounds& boundsFor(const SurfaceLayer& layer, PyramidLayout layout);
    /// The texel shadows the draw reads (nullptr: none): the policy's stride from the view, then
    /// the cached ones where they still hold, else drawn.
    /// `light` is the flat patch's (flatPatchLight; empty for a caster or where none is traced).
    const TexelShadows* texelShadowsFor(const SurfaceTextures& textures, HeightBounds& bounds, const Mesh& mesh,
                                        const glm::mat4& model, const glm::mat4& viewProj, const Viewport& viewport,
                                        const std::optional<ShadowLight>& light, const SurfaceMaterial& material,
                                        const DrawOptions& options, TracerFrame& frame);
    /// Sizes the deferred walks' buffer for the viewport and for what the last draw that
    /// deferred appended (where the GPU is past it), empties it and binds it.
    void prepareDeferred(const Viewport& viewport);
    /// A trial's draws: a mesh (Mesh::uid), seen by a camera (false) or a shadow caster (true).
    using TrialKey = std::pair<std::uint64_t, bool>;
    /// The trial of `key`, made where there is none (the least recently drawn of kTrials let go
    /// for it), and marked as drawn now.
    TracePassTrial& trialFor(const TrialKey& key);
    /// The pass of a draw of `key` that asked for `asked`, and whether it is one of the trial's
    /// timed draws.
    std::pair<TracePass, bool> tracePassFor(TracePass asked, const TrialKey& key);
    /// A trial draw's timing: begun once prepare's own passes are issued, ended by finish; the
    /// times of earlier draws the GPU has stamped since read without waiting.
    void beginTrialDraw(TracePass pass, const TrialKey& key);
    void endTrialDraw();
    void readTrialDraws();
    /// Gives a trial draw's time to its trial; where that decides for the draw, the compute
    /// pass's buffers go unless another trial may take it.
    void recordTrialDraw(const TrialKey& key, TracePass pass, double ms);
    /// finish()'s deferred light walks.
    void walkDeferred(const TracerFrame& frame);
    /// Sizes the computed walks' buffers for the viewport (the lights' where `lights`), stamps
    /// this draw, binds them and fills the uniform block's trace fields.
    void prepareComputeTrace(const Viewport& viewport, int planes, bool lights, SurfaceUniforms& u);
    /// Whether this context's vertex stage can read the deferred rays' buffer (GL 4.5 does not
    /// promise it; the compute stage that walks them has storage buffers and images).
    bool vertexStageReadsBuffer();
    struct PatchRays;
    /// The beam start of a flat patch whose rays `rays` finds (its budget and light unread), for
    /// `viewport`'s draw, into beamTarget_ (trace/hier/beam.comp); `u` the draw's block.
    void drawBeamStart(const PatchRays& rays, const Viewport& viewport, const SurfaceUniforms& u, bool atlas);

    BoundsPass boundsPass_;
    /// The bounds of the surfaces drawn lately, by SurfaceTextures::uid and layout (0: a free
    /// slot), the least recently used remade for a new surface: the ocean's four cascades of two
    /// texture pairs each fit.
    struct Bounds {
        std::uint64_t uid = 0, used = 0;
        std::unique_ptr<HeightBounds> bounds;
    };
    std::array<Bounds, 8> bounds_{};
    TexelShadowPass texelPass_;
    /// The texel shadows of the surfaces drawn lately, by SurfaceTextures::uid (a pipeline's
    /// two texture pairs each have theirs; 0: a free slot), the least recently used given to a
    /// new surface. A fixed array: what prepare() hands out stays where it is.
    struct Cached {
        std::uint64_t uid = 0, used = 0;
        TexelShadows shadows;
    };
    static constexpr size_t kCached = 4;
    std::array<Cached, kCached> cache_{};
    std::uint64_t clock_ = 0;
    /// The last stride drawn per mesh (Mesh::uid; 0: none), so the policy holds on near its
    /// threshold.
    std::map<std::uint64_t, int> strides_;
    TracerFrame last_, lastCaster_;
    std::optional<GlWorkarounds> workarounds_;
    ShaderProgram beam_[2]; ///< by the pyramid's layout: a mip chain, the atlas
    GlTexture beamTarget_; ///< R32F, a texel per block from the window's origin
    int beamWidth_ = 0, beamHeight_ = 0;
    GlBuffer block_; ///< the prepass's uniform block
    /// The deferred light walks: the buffer (trace/hier/deferred.glsl), its capacity in rays,
    /// their walk by the pyramid's layout, and the points that write their pixels.
    static constexpr size_t kDeferredHeader = 32, kDeferredRay = 64; // bytes: trace/hier/deferred.glsl
    static constexpr GLintptr kDeferredDispatch = 20;                // bytes: the dispatch command's offset
    GlBuffer deferred_;
    int deferredCapacity_ = 0;
    GlFence deferredDone_; ///< after the last pass that read the buffer: its count read once passed
    ShaderProgram deferredWalk_[2], deferredPixels_;
    GlVertexArray noVertices_;
    GLint vertexStorage_ = -1; ///< the context's limit, read once
    /// The computed walks (TracePass::Compute): a slot per pixel of the viewport in each buffer
    /// (trace/hier/trace.glsl; the lights' made when first needed, for as many slots), the stamp
    /// of the last draw, and the pass by its variant (the pyramid's layout, the beam start, the
    /// texel shadows, the lights).
    static constexpr size_t kTraceRay = 16, kTraceInfo = 8, kTraceLight = 8; // bytes a slot
    static constexpr std::uint32_t kTraceStamps = 32767; // a slot's mark holds 15 bits of it
    GlBuffer traceRays_, traceInfo_, traceLights_;
    int traceSlots_ = 0, traceWidth_ = 0, traceHeight_ = 0, tracePlanes_ = 1;
    std::uint32_t traceStamp_ = 0;
    std::map<int, ShaderProgram> traceWalks_;
    /// The flat patch the last draw with TracerFrame::patchRays placed, as trace.comp reads it
    /// (its HFX_TRACE_PATCH uniforms, which say what each is): the screen's map to its texcoords,
    /// clip depth over them, the eye in its texture space, its texcoords' box, the pixel budget,
    /// the light ray's texcoords per unit climbed (empty where the light is below the patch) and
    /// whether light rays are walked.
    struct PatchRays {
        glm::mat3 fromScreen{1.0f};
        glm::vec3 depth{0.0f}, eye{0.0f};
        glm::vec4 box{0.0f};
        float budget = 0.0f;
        std::optional<glm::vec2> light;
        bool walksLight = false;
    };
    /// The patch's rays as `model` and `viewProj` place it, seen from `u`'s eye (setEye's), its
    /// light from `lightDirection` (world, towards the light) at `depthScale`; empty where its
    /// frame is degenerate (no texture space: the rays draw normal maps it) or the view sees it
    /// edge on.
    static std::optional<PatchRays> patchRaysOf(const FlatPatch& patch, const glm::mat4& model,
                                                const glm::mat4& viewProj, const SurfaceUniforms& u,
                                                const glm::vec3& lightDirection, float depthScale);
    PatchRays patchRays_;
    /// TracePass::Auto's trials, per mesh and kind of view, and their timed draws whose GL
    /// timestamps are not yet read (ended where `end` is issued; or, with
    /// GlWorkarounds::cpuClockTimer, the one under way, timed by the CPU clock between two
    /// glFinish).
    /// (Each with the clock_ of its last draw: an engine that makes meshes as it goes would
    /// otherwise grow the map by one for every mesh it ever drew.)
    struct HeldTrial {
        TracePassTrial trial;
        std::uint64_t used = 0;
    };
    std::map<TrialKey, HeldTrial> trials_;
    struct TrialDraw {
        TracePass pass = TracePass::Auto;
        TrialKey key{0, false};
        GlQuery begin, end;
        std::chrono::steady_clock::time_point cpuBegin;
    };
    std::deque<TrialDraw> trialDraws_;
    static constexpr size_t kTrialDrawsWaiting = 64;
};

} // namespace hfx
