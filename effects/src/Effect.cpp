#include "hfx/effects/Effect.h"

namespace hfx {

Effect::Effect(const SurfaceMaterial& material) : material_((material.validate(), material)) {}

void Effect::setMaterial(const SurfaceMaterial& material) {
    material.validate();
    material_ = material;
}

// The pipelines are the derived class's members; the base only sequences them.
void Effect::begin(StageTiming timing) {
    for (const SurfacePipeline* s : surfaces()) const_cast<SurfacePipeline*>(s)->begin(timing);
}

void Effect::finish() {
    for (const SurfacePipeline* s : surfaces()) const_cast<SurfacePipeline*>(s)->finish();
}

void Effect::update(double dt) {
    begin(StageTiming::Staged);
    advance(dt);
    enqueueSurface();
    finish();
}

void Effect::beginUpdate(double dt) {
    begin(StageTiming::Overlapped);
    advance(dt);
    enqueueSurface();
}

void Effect::endUpdate() { finish(); }

void Effect::refresh() {
    begin(StageTiming::Staged);
    enqueueSurface();
    finish();
}

StageTimes Effect::lastTimes() const {
    const std::vector<const SurfacePipeline*> all = surfaces();
    if (all.size() == 1) return all[0]->lastTimes();
    // Staged: the source's step is the first pipeline's field time (the later ones begin after
    // it); each pipeline's own stages add. Overlapped: the waits add.
    StageTimes t = all[0]->lastTimes();
    t.compute = t.staged ? t.field : t.compute;
    for (size_t i = 0; i < all.size(); ++i) {
        const StageTimes s = all[i]->lastTimes();
        if (i > 0) {
            t.normals += s.normals;
            t.extra += s.extra;
            t.upload += s.upload;
            if (!t.staged) t.compute += s.compute;
        }
        if (t.staged) t.compute += s.normals + s.extra;
    }
    return t;
}

} // namespace hfx
