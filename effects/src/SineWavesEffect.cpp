#include "hfx/effects/SineWavesEffect.h"

namespace hfx {

void SineWavesConfig::validate() const {
    waves.validate();
    material.validate();
}

namespace {
std::unique_ptr<HeightSource> makeWaves(ClContext& cl, const SineWavesConfig& config) {
    config.validate();
    return std::make_unique<WaveField>(cl, config.waves);
}
} // namespace

SineWavesEffect::SineWavesEffect(ClContext& cl, const SineWavesConfig& config)
    : FieldEffect(cl, makeWaves(cl, config), config.material,
                  config.surface),
      waves_(static_cast<WaveField&>(source())) {
    setAlbedo(Image{1, 1, 3, {0.05f, 0.22f, 0.30f}});
}

void SineWavesEffect::setTime(double seconds) {
    const double start = nowMs();
    waves_.setTime(seconds);
    refresh(start);
}

} // namespace hfx
