#include "hfx/effects/SineWavesEffect.h"

#include "hfx/core/Error.h"

namespace hfx {

void SineWavesConfig::validate() const {
    waves.validate();
    material.validate();
}

SineWavesEffect::SineWavesEffect(ClContext& cl, const SineWavesConfig& config)
    : Effect(validated(config).material), waves_(cl, config.waves),
      surface_(cl, SurfacePipelineConfig::of(waves_, config.material.depthScale, config.surface)) {
    surface_.setAlbedo(Image{1, 1, 3, {0.05f, 0.22f, 0.30f}});
    refresh();
}

void SineWavesEffect::enqueueSurface() {
    surface_.derive(waves_.buffer());
    surface_.submit();
}

void SineWavesEffect::setTime(double seconds) {
    waves_.setTime(seconds);
    refresh();
}

} // namespace hfx
