#include "hfx/effects/FieldEffect.h"

#include "hfx/core/Error.h"
#include "hfx/effects/FieldUpload.h"

#include <chrono>

namespace hfx {
namespace {
const HeightSource& checked(const std::unique_ptr<HeightSource>& source) {
    if (!source) throw Error("FieldEffect needs a height source, got none");
    return *source;
}
SurfaceTexturesConfig texturesConfig(const HeightSource& source, bool mipmaps, bool pyramid, SurfaceFormat format) {
    return {.width = source.width(),
            .height = source.height(),
            .mipmaps = mipmaps,
            .edges = source.periodic()    ? EdgeMode::Wrap
                     : source.periodicU() ? EdgeMode::WrapU
                                          : EdgeMode::Clamp,
            .pyramid = pyramid,
            .format = format};
}

} // namespace

double FieldEffect::nowMs() {
    return std::chrono::duration<double, std::milli>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

FieldEffect::FieldEffect(ClContext& cl, std::unique_ptr<HeightSource> source,
                         const SurfaceMaterial& material, bool mipmaps, bool pyramid, SurfaceFormat format)
    : cl_(cl), material_((material.validate(), material)),
      normals_(cl, SobelConfig{.width = checked(source).width(),
                               .height = source->height(),
                               .depthScale = material.depthScale,
                               .wrapEdges = source->periodicU(),
                               .clampV = !source->periodic()}),
      textures_{std::make_unique<SurfaceTextures>(texturesConfig(*source, mipmaps, pyramid, format)),
                std::make_unique<SurfaceTextures>(texturesConfig(*source, mipmaps, pyramid, format))} {
    source_ = std::move(source);
    if (pyramid)
        pyramid_ = std::make_unique<MaxPyramid>(cl, source_->width(), source_->height(), source_->periodic());
    if (format != SurfaceFormat::Float32)
        packer_ = std::make_unique<SurfacePacker>(cl, source_->width(), source_->height(), format);
    refresh(nowMs());
}

void FieldEffect::stepSource(double dt) { source_->step(dt); }

void FieldEffect::setAlbedo(const Image& albedo) {
    for (auto& t : textures_) t->setAlbedo(albedo);
}

void FieldEffect::update(double dt) {
    if (pending_) endUpdate();
    const double start = nowMs();
    stepSource(dt);
    refresh(start);
}

void FieldEffect::beginUpdate(double dt) {
    if (pending_) endUpdate(); // never two in flight
    const double start = nowMs();
    stepSource(dt);
    normals_.run(source_->buffer());
    if (pyramid_) pyramid_->build(source_->buffer());
    enqueueExtra();
    if (packer_) packer_->run(normals_.output());
    clGuard("FieldEffect::beginUpdate", [&] {
        cl_.queue().enqueueMarkerWithWaitList(nullptr, &pendingDone_);
        cl_.queue().flush(); // start now, not at the wait
    });
    pending_ = true;
    pendingStart_ = start;
}

void FieldEffect::endUpdate() {
    if (!pending_) return;
    pending_ = false;
    const double waitStart = nowMs();
    clGuard("FieldEffect::endUpdate", [&] { pendingDone_.wait(); });
    const double computed = nowMs();
    upload();
    times_ = {.compute = computed - waitStart, .upload = nowMs() - computed, .field = 0, .normals = 0, .extra = 0};
}

void FieldEffect::upload() {
    SurfaceTextures& back = uploadTarget();
    if (packer_)
        uploadPacked(cl_, *packer_, back);
    else
        uploadField(cl_, normals_.output(), back);
    if (pyramid_) uploadPyramid(cl_, *pyramid_, back);
    uploadExtra();
    front_ = 1 - front_;
}

namespace {
double finishedMs(ClContext& cl) {
    clGuard("FieldEffect::update", [&] { cl.queue().finish(); });
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace

void FieldEffect::setDepthScale(float depthScale) {
    SurfaceMaterial next = material_;
    next.depthScale = depthScale;
    next.validate();
    normals_.setDepthScale(depthScale);
    material_ = next;
}

void FieldEffect::refresh(double computeStartMs) {
    pending_ = false; // an overlapped update in flight is part of what this waits for
    // Each stage is waited for, so the frame's budget can be read stage by stage; the queue is
    // in order and the CPU device runs one kernel at a time, so the waits cost no overlap.
    const double stepped = finishedMs(cl_);
    normals_.run(source_->buffer());
    const double normalised = finishedMs(cl_);
    if (pyramid_) pyramid_->build(source_->buffer());
    enqueueExtra();
    if (packer_) packer_->run(normals_.output());
    const double computed = finishedMs(cl_);
    upload();
    times_ = {.compute = computed - computeStartMs,
              .upload = nowMs() - computed,
              .field = stepped - computeStartMs,
              .normals = normalised - stepped,
              .extra = computed - normalised};
}

} // namespace hfx
