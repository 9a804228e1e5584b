#include "hfx/effects/WaterEffect.h"

namespace hfx {

void WaterConfig::validate() const {
    waves.validate();
    material.validate();
}

namespace {
std::unique_ptr<HeightSource> makeWaves(ClContext& cl, const WaterConfig& config) {
    config.validate();
    return std::make_unique<WaveField>(cl, config.waves);
}
} // namespace

WaterEffect::WaterEffect(ClContext& cl, const WaterConfig& config)
    : FieldEffect(cl, makeWaves(cl, config), config.material,
                  config.surface),
      waves_(static_cast<WaveField&>(source())) {
    setAlbedo(Image{1, 1, 3, {0.05f, 0.22f, 0.30f}});
}

void WaterEffect::setTime(double seconds) {
    const double start = nowMs();
    waves_.setTime(seconds);
    refresh(start);
}

} // namespace hfx
