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
                         const SurfaceMaterial& material, bool mipmaps)
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
                                                                     : EdgeMode::Clamp}) {
    source_ = std::move(source);
    refresh(nowMs());
}

void FieldEffect::update(double dt) {
    const double start = nowMs();
    source_->step(dt);
    refresh(start);
}

void FieldEffect::setDepthScale(float depthScale) {
    SurfaceMaterial next = material_;
    next.depthScale = depthScale;
    next.validate();
    normals_.setDepthScale(depthScale);
    material_ = next;
}

void FieldEffect::refresh(double computeStartMs) {
    normals_.run(source_->buffer());
    enqueueExtra();
    clGuard("FieldEffect::update", [&] { cl_.queue().finish(); });
    const double computed = nowMs();
    uploadField(cl_, normals_.output(), textures_);
    uploadExtra();
    times_ = {computed - computeStartMs, nowMs() - computed};
}

} // namespace hfx
