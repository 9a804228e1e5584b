#include "hfx/effects/tracer/ExactTracer.h"

#include "hfx/core/Bindings.h"
#include "hfx/core/Camera.h"
#include "hfx/core/Error.h"
#include "hfx/core/GlRenderer.h"
#include "hfx/core/GpuTimer.h"
#include "hfx/effects/Picking.h"
#include "hfx/effects/SurfaceRenderer.h"

#include "../GlStateGuard.h"

#include <algorithm>
#include <limits>

namespace hfx {

std::optional<ShadowLight> flatPatchLight(const Mesh& mesh, const glm::mat4& model, const DirectionalLight& light,
                                          const SurfaceMaterial& material) {
    if (!mesh.patch() || material.triplanar.on()) return std::nullopt;
    const FlatPatch& p = *mesh.patch();
    const glm::dmat4 m(model);
    const glm::dvec3 tangent(m * glm::dvec4(glm::dvec3(p.tangent), 0.0));
    const glm::dvec3 bitangent(m * glm::dvec4(glm::dvec3(p.bitangent), 0.0));
    const SurfaceFrame frame{.origin = glm::dvec3(m * glm::dvec4(glm::dvec3(p.origin), 1.0)),
                             .tangent = tangent,
                             .bitangent = bitangent,
                             .normal = glm::normalize(glm::cross(tangent, bitangent))};
    return flatSurfaceLight(frame, light, material);
}

TracerFrame ExactTracer::prepare(std::span<const SurfaceLayer> layers, const Mesh& mesh, const glm::mat4& model,
                                 const glm::mat4& viewProj, const DirectionalLight& light,
                                 const SurfaceMaterial& material, const DrawOptions& options, bool caster,
                                 SurfaceUniforms& u) {
    TracerFrame frame;
    const bool hier = techniqueInfo(options.technique).needsPyramid;
    const SurfaceTextures& textures = *layers[0].textures;
    const size_t traced = size_t(std::ranges::count_if(layers, [](const SurfaceLayer& l) { return l.traced; }));
    // Bounded searches where asked and every traced layer can carry bounds (the renderer checked
    // hier's layer).
    frame.boundedSearch = !hier && material.boundedSearch && std::ranges::all_of(layers, [](const SurfaceLayer& l) {
                              return !l.traced || carriesBounds(l.textures->config());
                          });
    const PyramidLayout layout = resolvedLayout(options.boundsLayout, workarounds());
    HeightBounds* bounds0 = nullptr;
    // The bounds the draw reads (hier's, a bounded search's traced layers'), built from the
    // current texels where they are older; hier's patch solve also reads the atlas layout's
    // cells (bound by the refresh of layer 0, the last).
    if (hier || frame.boundedSearch) {
        frame.atlas = layout == PyramidLayout::Atlas;
        for (size_t i = traced; i-- > 0;) {
            HeightBounds& bounds = boundsFor(layers[i], layout);
            boundsPass_.refresh(*layers[i].textures, bounds, i == 0 && hier);
            bounds.bind(int(i));
            if (i == 0) bounds0 = &bounds;
        }
    }
    glBindTextureUnit(HFX_UNIT_TEXEL_SHADOWS, 0);
    if (!hier) return frame;
    // The viewport, read once for every pass below.
    Viewport viewport;
    glGetIntegerv(GL_VIEWPORT, viewport.data());

    // The walks in a compute pass where asked (or the device's choice) and where the rays draw
    // and the shading draw meet the same pixels once each: a view (a camera's, a caster's) of a
    // convex mesh (its front faces a fragment per pixel at most; a back face's is normal mapped),
    // drawn without a stencil test (the rays draw would run its operations) into a
    // single-sampled target (one fragment a pixel).
    // Auto: the device's workaround, else the trial's side (only draws that could take either
    // side are timed for it).
    const bool inDrawOnly = options.tracePass == TracePass::InDraw ||
                            (options.tracePass == TracePass::Auto && workarounds().traceInDraw);
    // (A triplanar mapping's projections each walk their own ray: three planes of slots.)
    const bool triplanar = material.triplanar.on();
    bool computable = false;
    if (!inDrawOnly && mesh.convex() && layers.size() == 1 && material.depthScale > 0.0f &&
        !glIsEnabled(GL_STENCIL_TEST)) {
        GLint samples = 0;
        glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
        computable = samples == 0;
    }
    const auto [pass, timed] = computable ? tracePassFor(options.tracePass, {mesh.uid(), caster})
                                          : std::pair{TracePass::InDraw, false};
    frame.computeTrace = pass == TracePass::Compute;

    // The flat patch's light: every pixel's light ray, the texel shadows' (none for a caster: it
    // writes depth only).
    const std::optional<ShadowLight> patchLight = caster ? std::nullopt : flatPatchLight(mesh, model, light, material);
    frame.texelShadows =
        caster ? nullptr
               : texelShadowsFor(textures, *bounds0, mesh, model, viewProj, viewport, patchLight, material, options, frame);
    if (frame.texelShadows) {
        const ShadowLight& l = *frame.texelShadows->light();
        u.shadowLight = {l.uvPerClimb, l.penumbra, l.slack};
        glBindTextureUnit(HFX_UNIT_TEXEL_SHADOWS, frame.texelShadows->texture());
    }

    // The light walks the texel shadows do not hold, left to finish() where asked: not where the
    // shading is not affine in the light (the pass rebuilds the colour from two shadings), the
    // draw's pixels are blended or stencilled (finish writes them a second time), its trace
    // output read, or the context's vertex stage cannot read the buffer to place the pixels
    // (GL asks it of none).
    frame.deferredShadows = !frame.computeTrace && frame.texelShadows && options.deferShadowWalks &&
                            shadingAffineInLight(material.shading) &&
                            !options.traceOutput && !glIsEnabled(GL_BLEND) && !glIsEnabled(GL_STENCIL_TEST) &&
                            vertexStageReadsBuffer();
    if (frame.deferredShadows) prepareDeferred(viewport);
    // A flat patch's rays from the screen, where one frame holds for every pixel (no silhouette
    // fade scales its depth pixel by pixel): the beam start's and the compute pass's.
    std::optional<PatchRays> patchRays;
    if (mesh.patch() && material.silhouetteFade == 0.0f && !triplanar)
        patchRays = patchRaysOf(*mesh.patch(), model, viewProj, u, light.direction, material.depthScale);
    if (frame.computeTrace) {
        // Every pixel's light ray is the flat patch's light (the texel shadows' where they are
        // read) where it has one and no silhouette fade scales its depth pixel by pixel; else the
        // rays draw stores each pixel's. A caster's pass walks no light ray.
        const bool uniformLight = patchLight && material.silhouetteFade == 0.0f;
        if (uniformLight) u.shadowLight = {patchLight->uvPerClimb, patchLight->penumbra, patchLight->slack};
        // A flat patch's rays are found from the screen where one frame holds for every pixel.
        // (The rays draw's fragments walk the light ray where self-shadows are drawn, but for a
        // caster's, and the light is above the polygon: the texel shadows' light where there is
        // one.)
        if (patchRays) {
            frame.patchRays = true;
            patchRays_ = *patchRays;
            patchRays_.budget = caster ? 0.0f : material.pixelBudget;
            patchRays_.walksLight = material.shadows && !caster && patchRays->light.has_value();
            if (uniformLight) patchRays_.light = patchLight->uvPerClimb;
        }
        frame.traceLights = !frame.patchRays && !uniformLight && material.shadows && !caster;
        frame.tracePlanes = triplanar ? 3 : 1;
        prepareComputeTrace(viewport, frame.tracePlanes, frame.traceLights, u);
    }

    // The beam start holds only where a block's rays meet one plane in one frame at one depth:
    // they are found from the screen as the patch's.
    frame.beamStart = options.beamStart && layers.size() == 1 && patchRays && material.depthScale > 0.0f;
    if (frame.beamStart) { // the prepass reads the surface, the pyramid bound above and the block
        glBindTextureUnit(HFX_UNIT_SURFACE, textures.surface());
        const GpuScope scope("beam");
        drawBeamStart(*patchRays, viewport, u, frame.atlas);
        glBindTextureUnit(HFX_UNIT_BEAM_START, beamTarget_.id());
    }
    // A trial draw is timed from here (what comes before is the same on either side) to finish().
    if (timed) {
        beginTrialDraw(pass, {mesh.uid(), caster});
        frame.timed = true;
    }
    (caster ? lastCaster_ : last_) = frame;
    return frame;
}

TracePassTrialReport ExactTracer::passTrial(const Mesh& mesh, bool caster) const {
    const auto held = trials_.find({mesh.uid(), caster});
    return held == trials_.end() ? TracePassTrialReport{} : held->second.trial.report();
}

TracePassTrial& ExactTracer::trialFor(const TrialKey& key) {
    auto held = trials_.find(key);
    if (held == trials_.end()) {
        // The least recently drawn goes, but not one with a draw still waiting for its time (a
        // trial made again for the same key would take it).
        if (trials_.size() >= kTrials) {
            auto oldest = trials_.end();
            for (auto t = trials_.begin(); t != trials_.end(); ++t) {
                const bool waits = std::ranges::any_of(trialDraws_, [&](const TrialDraw& d) { return d.key == t->first; });
                if (!waits && (oldest == trials_.end() || t->second.used < oldest->second.used)) oldest = t;
            }
            if (oldest != trials_.end()) trials_.erase(oldest);
        }
        held = trials_.emplace(key, HeldTrial{}).first;
    }
    held->second.used = ++clock_;
    return held->second.trial;
}

std::pair<TracePass, bool> ExactTracer::tracePassFor(TracePass asked, const TrialKey& key) {
    if (asked != TracePass::Auto) return {asked, false};
    readTrialDraws();
    const TracePassTrial& trial = trialFor(key);
    // (A driver whose timestamps never come back would hold a query pair a draw: past a frame's
    // worth of draws waiting, the turns go on untimed.)
    return {trial.next(), !trial.decided() && trialDraws_.size() < kTrialDrawsWaiting};
}

void ExactTracer::beginTrialDraw(TracePass pass, const TrialKey& key) {
    // A draw begun and never ended (it threw between prepare and finish) is not counted.
    if (!trialDraws_.empty() && !trialDraws_.back().end) {
        const TrialDraw& open = trialDraws_.back();
        recordTrialDraw(open.key, open.pass, std::numeric_limits<double>::quiet_NaN());
        trialDraws_.pop_back();
    }
    trials_.at(key).trial.began(pass); // (tracePassFor made it for this draw)
    TrialDraw& d = trialDraws_.emplace_back();
    d.pass = pass;
    d.key = key;
    if (workarounds().cpuClockTimer) {
        glFinish();
        d.cpuBegin = std::chrono::steady_clock::now();
    } else {
        d.begin = GlQuery::create();
        glQueryCounter(d.begin.id(), GL_TIMESTAMP);
    }
}

void ExactTracer::endTrialDraw() {
    if (trialDraws_.empty() || trialDraws_.back().end) return;
    TrialDraw& d = trialDraws_.back();
    if (workarounds().cpuClockTimer) {
        glFinish();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - d.cpuBegin).count();
        const TrialDraw done = std::move(d);
        trialDraws_.pop_back();
        recordTrialDraw(done.key, done.pass, ms);
    } else {
        d.end = GlQuery::create();
        glQueryCounter(d.end.id(), GL_TIMESTAMP);
    }
}

void ExactTracer::readTrialDraws() {
    // In the order they began, each once the GPU has stamped its end: no wait.
    while (!trialDraws_.empty() && trialDraws_.front().end) {
        const TrialDraw& d = trialDraws_.front();
        GLint available = 0;
        glGetQueryObjectiv(d.end.id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) break;
        GLuint64 begin = 0, end = 0;
        glGetQueryObjectui64v(d.begin.id(), GL_QUERY_RESULT, &begin);
        glGetQueryObjectui64v(d.end.id(), GL_QUERY_RESULT, &end);
        const double ms = end >= begin ? double(end - begin) * 1e-6 : std::numeric_limits<double>::quiet_NaN();
        const TracePass pass = d.pass;
        const TrialKey key = d.key;
        trialDraws_.pop_front();
        recordTrialDraw(key, pass, ms);
    }
}

void ExactTracer::recordTrialDraw(const TrialKey& key, TracePass pass, double ms) {
    TracePassTrial& trial = trials_.at(key).trial; // (not let go while a draw waits)
    const bool wasDecided = trial.decided();
    trial.record(pass, ms);
    if (wasDecided || !trial.decided() || trial.next() != TracePass::InDraw) return;
    // Decided for the draw: the compute pass's buffers go, unless another trial may take it (a
    // draw that asks for the compute pass makes them again).
    const bool computeMayRun = std::ranges::any_of(trials_, [](const auto& t) {
        const TracePassTrial& other = t.second.trial;
        return other.decided() ? other.next() == TracePass::Compute : other.started();
    });
    if (computeMayRun) return;
    traceRays_ = {};
    traceInfo_ = {};
    traceLights_ = {};
    traceSlots_ = 0;
    traceWalks_.clear();
}

HeightBounds& ExactTracer::boundsFor(const SurfaceLayer& layer, PyramidLayout layout) {
    const SurfaceTextures& textures = *layer.textures;
    auto held = std::ranges::find_if(bounds_, [&](const Bounds& b) {
        return b.uid == textures.uid() && b.bounds->layout() == layout;
    });
    // The producer's, where they hold these texels (and noted as read, built or not, so it goes
    // on building them); those held here for the same textures are then let go.
    if (HeightBounds* given = layer.bounds; given && given->layout() == layout && given->fits(textures.config())) {
        given->noteWanted();
        if (given->holds(textures)) {
            if (held != bounds_.end()) *held = Bounds{};
            return *given;
        }
    }
    if (held == bounds_.end()) {
        held = std::ranges::min_element(bounds_, {}, &Bounds::used); // a free slot's is 0
        *held = Bounds{.uid = textures.uid(), .bounds = std::make_unique<HeightBounds>(textures.config(), layout)};
    }
    held->used = ++clock_;
    return *held->bounds;
}

const TexelShadows* ExactTracer::texelShadowsFor(const SurfaceTextures& textures, HeightBounds& bounds, const Mesh& mesh,
                                                 const glm::mat4& model, const glm::mat4& viewProj,
                                                 const Viewport& viewport, const std::optional<ShadowLight>& light,
                                                 const SurfaceMaterial& material, const DrawOptions& options,
                                                 TracerFrame& frame) {
    if (!mesh.patch()) return nullptr;
    const SurfaceTexturesConfig& field = textures.config();
    std::array<glm::vec3, 4> corners;
    for (size_t i = 0; i < corners.size(); ++i)
        corners[i] = glm::vec3(model * glm::vec4(mesh.patch()->corners[i], 1.0f));
    const double pixels = screenArea(corners, viewProj, viewport[2], viewport[3]);
    frame.pixelsPerTexel = pixels / (double(field.width) * field.height);
    if (options.texelShadows == TexelShadowChoice::Off) return nullptr;
    if (!light) return nullptr; // no shadow ray is traced
    // With the walks in a compute pass they do not pay: on the H200 (docs/BENCHMARKS.md) the
    // pixels' own light walks there cost about what reading them saved, and their pass cost
    // 0.03-0.14 ms after each change of heights.
    if (options.texelShadows == TexelShadowChoice::Auto && frame.computeTrace) return nullptr;
    // Every sample where that pays; under a pixel budget, every few samples where their spacing
    // on screen stays within it; forced on: the stride asked for, or the policy's, or every one.
    if (strides_.size() > 64) strides_.clear(); // meshes come and go: a held choice is a hint
    int& held = strides_[mesh.uid()];
    int stride = texelShadowStride(pixels, field.width, field.height, material.pixelBudget, held);
    if (options.texelShadows == TexelShadowChoice::On)
        stride = options.texelStride != 0 ? options.texelStride : std::max(stride, 1);
    if (stride != 0 && !isTexelStride(stride, field.width, field.height))
        throw Error(str("DrawOptions::texelStride must be a power of two that divides the field's ", field.width, "x",
                        field.height, " samples, got ", stride));
    held = stride;
    if (stride == 0) return nullptr;
    frame.texelStride = stride;
    // This surface's, kept while its texels and the light stay; else the least recently used's.
    auto it = std::ranges::find_if(cache_, [&](const Cached& c) { return c.uid == textures.uid(); });
    if (it == cache_.end()) {
        it = std::ranges::min_element(cache_, {}, &Cached::used); // a free slot's is 0
        it->uid = textures.uid();
    }
    it->used = ++clock_;
    if (!it->shadows.holds(textures, *light, stride)) texelPass_.draw(textures, bounds, *light, stride, it->shadows);
    return &it->shadows;
}

bool ExactTracer::vertexStageReadsBuffer() {
    if (vertexStorage_ < 0) glGetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &vertexStorage_);
    return vertexStorage_ >= 1;
}

void ExactTracer::prepareDeferred(const Viewport& viewport) {
    // Room for a ray per 16 pixels of the viewport, at least 256 (the cells a hard shadow's edge
    // crosses hold 0.4-3% of a view's pixels on smooth waves, up to 21% on a brick wall:
    // bench-tracers' 'deferred rays'); a ray past it is walked in the draw. Where the last draw
    // that deferred appended more and the GPU is past it (its count read back without waiting),
    // room for that and a quarter more, up to a ray per 4 pixels (64 bytes a ray: 15 MB at
    // 1280x720, 133 MB at 3840x2160): a view that keeps its rays walks them all after.
    // The last deferring draw's and pass's shader writes before the count is read back and the
    // header rewritten, and before this draw's appends overwrite the rays the last points read.
    if (deferred_) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    const int pixels = std::max(viewport[2] * viewport[3], 1);
    int capacity = std::max(pixels / 16, 256);
    if (deferredDone_.done()) {
        const int appended = deferredWalks();
        if (appended > deferredCapacity_)
            capacity = std::max(capacity, int(std::min(appended * 1.25, double(pixels) / 4.0)));
        deferredDone_ = GlFence();
    }
    if (capacity > deferredCapacity_ || !deferred_) {
        deferredCapacity_ = capacity;
        deferred_ = GlBuffer::create();
        HFX_GL_CHECK(glNamedBufferStorage(deferred_.id(), GLsizeiptr(kDeferredHeader + size_t(capacity) * kDeferredRay),
                                          nullptr, GL_DYNAMIC_STORAGE_BIT));
    }
    // A draw-indirect command of no points yet, one instance; the capacity; a dispatch command
    // of no groups yet.
    const std::array<GLuint, 8> header{0, 1, 0, 0, GLuint(deferredCapacity_), 0, 1, 1};
    static_assert(sizeof header == kDeferredHeader && kDeferredDispatch == 5 * sizeof(GLuint));
    HFX_GL_CHECK(glNamedBufferSubData(deferred_.id(), 0, sizeof header, header.data()));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HFX_BUFFER_DEFERRED_SHADOWS, deferred_.id());
}

void ExactTracer::finish(const TracerFrame& frame) {
    if (frame.deferredShadows) {
        const GpuScope scope("deferred walks");
        walkDeferred(frame);
    }
    if (frame.timed) endTrialDraw();
}

void ExactTracer::walkDeferred(const TracerFrame& frame) {
    ShaderProgram& walk = deferredWalk_[frame.atlas ? 1 : 0];
    if (!walk.id())
        walk = ShaderProgram::compute(surfaceStage("trace/hier/deferred.comp"),
                                      {{"HFX_LAYERS", "1"}, {"HFX_PYRAMID_ATLAS", frame.atlas ? "1" : "0"}});
    if (!deferredPixels_.id())
        deferredPixels_ = ShaderProgram(surfaceStage("trace/hier/deferred.vert"), surfaceStage("trace/hier/deferred.frag"));
    if (!noVertices_) noVertices_ = GlVertexArray::create();
    // The draw's appends, its commands' counts among them, before the walks read them; the
    // walks' colours before the points read them.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    walk.use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, deferred_.id());
    glDispatchComputeIndirect(kDeferredDispatch);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    deferredPixels_.use();
    deferredPixels_.set("u_viewport", glm::vec4(viewport[0], viewport[1], viewport[2], viewport[3]));
    // Where the draw's depth still stands (it tested GL_LESS and wrote it): nothing nearer
    // drawn over the pixel since, not a fragment of the draw that another covered.
    // Colour buffer 0 only: the draw wrote the pixels' motion (setMotionOutput), and a point
    // without that output would leave it undefined.
    const DrawBuffersWritten written(1u);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glBindVertexArray(noVertices_.id());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, deferred_.id());
    glDrawArraysIndirect(GL_POINTS, nullptr);
    deferredDone_ = GlFence::insert();
}

const GlWorkarounds& ExactTracer::workarounds() {
    if (!workarounds_) workarounds_ = glWorkarounds(currentGlRenderer());
    return *workarounds_;
}

void ExactTracer::prepareComputeTrace(const Viewport& viewport, int planes, bool lights, SurfaceUniforms& u) {
    const int slots = std::max(viewport[2], 1) * std::max(viewport[3], 1) * planes;
    // The last computed draw's shading draw reads its slots before this one's rays draw writes them.
    if (traceRays_) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    // A stamp per draw tells a slot this draw's rays draw wrote from another's (a helper lane past
    // the mesh's edge reads one): fresh buffers are cleared, and cleared again before the stamp
    // could wrap, so no slot holds a stamp not yet given.
    if (slots > traceSlots_ || traceStamp_ >= kTraceStamps) {
        traceSlots_ = std::max(slots, traceSlots_);
        traceRays_ = GlBuffer::create();
        traceInfo_ = GlBuffer::create();
        HFX_GL_CHECK(glNamedBufferStorage(traceRays_.id(), GLsizeiptr(size_t(traceSlots_) * kTraceRay), nullptr, 0));
        HFX_GL_CHECK(glNamedBufferStorage(traceInfo_.id(), GLsizeiptr(size_t(traceSlots_) * kTraceInfo), nullptr, 0));
        const GLuint zero = 0;
        glClearNamedBufferData(traceInfo_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        traceLights_ = {};
        traceStamp_ = 0;
    }
    // (A slot's light is read only where this draw's rays draw marked it walked, and wrote it.)
    if (lights && !traceLights_) {
        traceLights_ = GlBuffer::create();
        HFX_GL_CHECK(glNamedBufferStorage(traceLights_.id(), GLsizeiptr(size_t(traceSlots_) * kTraceLight), nullptr, 0));
    }
    ++traceStamp_;
    traceWidth_ = std::max(viewport[2], 1);
    traceHeight_ = std::max(viewport[3], 1);
    tracePlanes_ = planes;
    u.traceWidth = traceWidth_;
    u.traceStamp = traceStamp_;
    u.traceOrigin = {viewport[0], viewport[1]};
    u.traceHeight = traceHeight_;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HFX_BUFFER_TRACE_RAYS, traceRays_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HFX_BUFFER_TRACE_INFO, traceInfo_.id());
    if (lights) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HFX_BUFFER_TRACE_LIGHTS, traceLights_.id());
}

std::optional<ExactTracer::PatchRays> ExactTracer::patchRaysOf(const FlatPatch& patch, const glm::mat4& model,
                                                             const glm::mat4& viewProj, const SurfaceUniforms& u,
                                                             const glm::vec3& lightDirection, float depthScale) {
    // surface.vert's frame (dP/du, dP/dv by the model, the normal by its inverse transpose) and
    // surface.frag's texture space of it (hfx_world_from_texture), in doubles.
    const glm::dmat4 m(model);
    const glm::dmat3 linear(m);
    const glm::dvec3 tangent = linear * glm::dvec3(patch.tangent), bitangent = linear * glm::dvec3(patch.bitangent);
    const glm::dvec3 normal = glm::normalize(glm::transpose(glm::inverse(linear)) * glm::dvec3(patch.normal));
    const double t = glm::length(tangent), b = glm::length(bitangent);
    if (!(t > 1e-3 * b && b > 1e-3 * t)) return std::nullopt; // (surface.frag's test for a texture space)
    const glm::dmat3 worldFromTexture(tangent, bitangent, normal * std::sqrt(t * b));
    if (!(std::abs(glm::determinant(worldFromTexture)) > 1e-9 * t * b * std::sqrt(t * b))) return std::nullopt;
    const glm::dmat3 textureFromWorld = glm::inverse(worldFromTexture);
    const glm::dvec3 origin(m * glm::dvec4(glm::dvec3(patch.origin), 1.0));
    // Clip coordinates of the point at (u, v): c0 + u cu + v cv. Their x, y and w, a 3x3 map of
    // (u, v, 1); the screen's map back is its inverse, where the view does not see the patch edge
    // on (or from its plane).
    const glm::dmat4 vp(viewProj);
    const glm::dvec4 c0 = vp * glm::dvec4(origin, 1.0), cu = vp * glm::dvec4(tangent, 0.0),
                     cv = vp * glm::dvec4(bitangent, 0.0);
    const glm::dmat3 toScreen(glm::dvec3(cu.x, cu.y, cu.w), glm::dvec3(cv.x, cv.y, cv.w), glm::dvec3(c0.x, c0.y, c0.w));
    const double scale = glm::length(glm::dvec3(cu.x, cu.y, cu.w)) * glm::length(glm::dvec3(cv.x, cv.y, cv.w)) *
                         glm::length(glm::dvec3(c0.x, c0.y, c0.w));
    if (!(std::abs(glm::determinant(toScreen)) > 1e-9 * scale)) return std::nullopt;
    // surface.frag's light in texture space, and its ray's texcoords per unit climbed.
    const glm::dvec3 l = textureFromWorld * glm::normalize(glm::dvec3(lightDirection));
    PatchRays rays;
    rays.fromScreen = glm::mat3(glm::inverse(toScreen));
    rays.depth = glm::vec3(cu.z, cv.z, c0.z);
    rays.eye = glm::vec3(textureFromWorld * (u.orthographic != 0 ? glm::dvec3(u.towardsEye)
                                                                  : glm::dvec3(u.cameraPos) - origin));
    rays.box = glm::vec4(patch.texcoordMin, patch.texcoordMax);
    if (l.z > 0.0 && glm::dot(normal, glm::dvec3(lightDirection)) > 0.0)
        rays.light = glm::vec2(glm::dvec2(l) / l.z * double(depthScale));
    return rays;
}

void ExactTracer::walks(const TracerFrame& frame) {
    if (!frame.computeTrace) return;
    const bool beam = frame.beamStart, texel = frame.texelShadows != nullptr, lights = frame.traceLights;
    const bool patch = frame.patchRays;
    ShaderProgram& walk =
        traceWalks_[int(frame.atlas) | int(beam) << 1 | int(texel) << 2 | int(lights) << 3 | int(patch) << 4];
    if (!walk.id())
        walk = ShaderProgram::compute(surfaceStage("trace/hier/trace.comp"),
                                      {{"HFX_LAYERS", "1"},
                                       {"HFX_PYRAMID_ATLAS", frame.atlas ? "1" : "0"},
                                       {"HFX_BEAM_START", beam ? "1" : "0"},
                                       {"HFX_TEXEL_SHADOWS", texel ? "1" : "0"},
                                       {"HFX_TRACE_LIGHTS", lights ? "1" : "0"},
                                       {"HFX_TRACE_PATCH", patch ? "1" : "0"}});
    // The rays draw's stores before the walks read them; the walks' before the shading draw's.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    walk.use();
    if (patch) {
        const PatchRays& r = patchRays_;
        walk.set("u_patchFromScreen", r.fromScreen);
        walk.set("u_patchDepth", r.depth);
        walk.set("u_patchEye", r.eye);
        walk.set("u_patchBox", r.box);
        walk.set("u_patchBudget", r.budget);
        walk.set("u_patchWalksLight", r.walksLight ? 1 : 0);
        walk.set("u_patchLight", r.light.value_or(glm::vec2(0.0f)));
    }
    walk.set("u_tracePlanes", tracePlanes_);
    walk.dispatchOver(traceWidth_, traceHeight_ * tracePlanes_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

TracerMemory ExactTracer::memory() const {
    TracerMemory m;
    const size_t slot = kTraceRay + kTraceInfo + (traceLights_ ? kTraceLight : 0);
    if (traceRays_) m.slots = size_t(traceSlots_) * slot;
    for (const Bounds& b : bounds_)
        if (b.bounds) m.bounds += b.bounds->bytes();
    for (const Cached& c : cache_) m.texelShadows += c.shadows.bytes();
    if (beamTarget_) m.prepasses += size_t(beamWidth_) * size_t(beamHeight_) * 4; // R32F
    if (deferred_) m.prepasses += kDeferredHeader + size_t(deferredCapacity_) * kDeferredRay;
    return m;
}

void ExactTracer::release() {
    traceRays_ = {};
    traceInfo_ = {};
    traceLights_ = {};
    traceSlots_ = 0;
    traceStamp_ = 0;
    for (Bounds& b : bounds_) b = Bounds{};
    // (The entries stay where they are: a frame prepare() handed out points at one.)
    for (Cached& c : cache_) c = Cached{};
    beamTarget_ = {};
    beamWidth_ = beamHeight_ = 0;
    deferred_ = {};
    deferredCapacity_ = 0;
    deferredDone_ = {};
}

int ExactTracer::deferredWalks() const {
    if (!deferred_) return 0;
    GLuint count = 0;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // the draw's atomic count, written by a shader
    glGetNamedBufferSubData(deferred_.id(), 0, sizeof count, &count);
    return int(count);
}

void ExactTracer::drawBeamStart(const PatchRays& rays, const Viewport& viewport, const SurfaceUniforms& u,
                                bool atlas) {
    // Texel (i, j) covers the window's pixels [B i, B i + B) x [B j, B j + B): the target spans
    // the viewport's far corner.
    const int width = std::max((viewport[0] + viewport[2] + kBeamBlock - 1) / kBeamBlock, 1);
    const int height = std::max((viewport[1] + viewport[3] + kBeamBlock - 1) / kBeamBlock, 1);
    if (width > beamWidth_ || height > beamHeight_ || !beamTarget_) {
        beamWidth_ = std::max(width, beamWidth_);
        beamHeight_ = std::max(height, beamHeight_);
        beamTarget_ = GlTexture::create();
        HFX_GL_CHECK(glTextureStorage2D(beamTarget_.id(), 1, GL_R32F, beamWidth_, beamHeight_));
        glTextureParameteri(beamTarget_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(beamTarget_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    ShaderProgram& beam = beam_[atlas ? 1 : 0];
    if (!beam.id())
        beam = ShaderProgram::compute(surfaceStage("trace/hier/beam.comp"),
                                      {{"HFX_LAYERS", "1"}, {"HFX_PYRAMID_ATLAS", atlas ? "1" : "0"}});
    updateBlock(block_, HFX_BLOCK_SURFACE, u);
    beam.use();
    beam.set("u_patchFromScreen", rays.fromScreen);
    beam.set("u_patchEye", rays.eye);
    beam.set("u_patchBox", rays.box);
    beam.set("u_beamViewport", glm::vec4(viewport[0], viewport[1], viewport[2], viewport[3]));
    beam.set("u_beamBlocks", glm::ivec2(width, height));
    HFX_GL_CHECK(glBindImageTexture(HFX_IMAGE_PASS_OUTPUT, beamTarget_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F));
    beam.dispatchOver(width, height);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT); // the draw or the walks pass reads it
}

} // namespace hfx
