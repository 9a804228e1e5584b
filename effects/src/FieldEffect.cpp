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
} // namespace

double FieldEffect::nowMs() {
    return std::chrono::duration<double, std::milli>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

FieldEffect::FieldEffect(ClContext& cl, std::unique_ptr<HeightSource> source,
                         const SurfaceMaterial& material, bool mipmaps, bool pyramid)
    : cl_(cl), material_((material.validate(), material)),
      normals_(cl, SobelConfig{.width = checked(source).width(),
                               .height = source->height(),
                               .depthScale = material.depthScale,
                               .wrapEdges = source->periodicU(),
                               .clampV = !source->periodic()}),
      textures_(SurfaceTexturesConfig{.width = source->width(),
                                      .height = source->height(),
                                      .mipmaps = mipmaps,
                                      .edges = source->periodic()    ? EdgeMode::Wrap
                                               : source->periodicU() ? EdgeMode::WrapU
                                                                     : EdgeMode::Clamp,
                                      .pyramid = pyramid}) {
    source_ = std::move(source);
    if (pyramid)
        pyramid_ = std::make_unique<MaxPyramid>(cl, source_->width(), source_->height(), source_->periodic());
    refresh(nowMs());
}

void FieldEffect::update(double dt) {
    const double start = nowMs();
    source_->step(dt);
    refresh(start);
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
    // Each stage is waited for, so the frame's budget can be read stage by stage; the queue is
    // in order and the CPU device runs one kernel at a time, so the waits cost no overlap.
    const double stepped = finishedMs(cl_);
    normals_.run(source_->buffer());
    const double normalised = finishedMs(cl_);
    if (pyramid_) pyramid_->build(source_->buffer());
    enqueueExtra();
    const double computed = finishedMs(cl_);
    uploadField(cl_, normals_.output(), textures_);
    if (pyramid_) uploadPyramid(cl_, *pyramid_, textures_);
    uploadExtra();
    times_ = {.compute = computed - computeStartMs,
              .upload = nowMs() - computed,
              .field = stepped - computeStartMs,
              .normals = normalised - stepped,
              .extra = computed - normalised};
}

} // namespace hfx
