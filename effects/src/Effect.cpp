#include "hfx/effects/Effect.h"

namespace hfx {

Effect::Effect(const SurfaceMaterial& material) : material_((material.validate(), material)) {}

void Effect::setMaterial(const SurfaceMaterial& material) {
    material.validate();
    material_ = material;
}

void Effect::update(double dt) {
    surface().begin(StageTiming::Staged);
    advance(dt);
    enqueueSurface();
    surface().finish();
}

void Effect::beginUpdate(double dt) {
    surface().begin(StageTiming::Overlapped);
    advance(dt);
    enqueueSurface();
}

void Effect::endUpdate() { surface().finish(); }

void Effect::refresh() {
    surface().begin(StageTiming::Staged);
    enqueueSurface();
    surface().finish();
}

} // namespace hfx
