#include "hfx/effects/OceanEffect.h"

#include "hfx/core/Error.h"

#include <algorithm>
#include <cmath>

namespace hfx {

void OceanEffectConfig::validate() const {
    ocean.validate();
    material.validate();
    if (!(reliefExaggeration > 0.0f && reliefExaggeration <= 20.0f))
        throw Error(str("OceanEffectConfig.reliefExaggeration must be in (0, 20], got ", reliefExaggeration));
}

namespace {
std::unique_ptr<HeightSource> makeOcean(ClContext& cl, const OceanEffectConfig& config) {
    config.validate();
    return std::make_unique<OceanField>(cl, config.ocean);
}
} // namespace

OceanEffect::OceanEffect(ClContext& cl, const OceanEffectConfig& config)
    : FieldEffect(cl, makeOcean(cl, config), config.material,
                  config.surface),
      ocean_(static_cast<OceanField&>(source())), exaggeration_(config.reliefExaggeration) {
    setDepthScale(physicalDepthScale());
    refresh(nowMs());
}

float OceanEffect::physicalDepthScale() const {
    const float depth = 8.0f * ocean_.sigmaMeters() / ocean_.config().patchMeters * exaggeration_;
    return std::clamp(depth, 1e-4f, 1.0f);
}

void OceanEffect::setWind(float speed, float direction) {
    const double start = nowMs();
    ocean_.setWind(speed, direction);
    setDepthScale(physicalDepthScale());
    refresh(start);
}

void OceanEffect::setTime(double seconds) {
    const double start = nowMs();
    ocean_.setTime(seconds);
    refresh(start);
}

} // namespace hfx
