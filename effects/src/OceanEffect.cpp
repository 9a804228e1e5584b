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

OceanEffect::OceanEffect(ClContext& cl, const OceanEffectConfig& config)
    : Effect(validated(config).material), ocean_(cl, config.ocean), exaggeration_(config.reliefExaggeration),
      // Normals for the sea state the ocean starts in; later winds are rescaled by the renderer.
      surface_(cl, SurfacePipelineConfig::of(ocean_, physicalDepthScale(), config.surface)) {
    material_.depthScale = physicalDepthScale();
    refresh();
}

float OceanEffect::physicalDepthScale() const {
    const float depth = 8.0f * ocean_.sigmaMeters() / ocean_.config().patchMeters * exaggeration_;
    return std::clamp(depth, 1e-4f, 1.0f);
}

void OceanEffect::enqueueSurface() {
    surface_.derive(ocean_.buffer());
    surface_.submit();
}

void OceanEffect::setWind(float speed, float direction) {
    ocean_.setWind(speed, direction);
    material_.depthScale = physicalDepthScale();
    refresh();
}

void OceanEffect::setTime(double seconds) {
    ocean_.setTime(seconds);
    refresh();
}

} // namespace hfx
