#include "hfx/effects/NoiseSurfaceEffect.h"

#include "hfx/core/Error.h"

namespace hfx {

std::vector<ColorStop> noisePalette() {
    return {{0.0f, {0.16f, 0.12f, 0.09f}}, {0.3f, {0.36f, 0.29f, 0.22f}}, {0.5f, {0.52f, 0.48f, 0.42f}},
            {0.7f, {0.66f, 0.64f, 0.6f}},   {0.88f, {0.8f, 0.79f, 0.76f}}, {1.0f, {0.93f, 0.93f, 0.92f}}};
}

void NoiseSurfaceConfig::validate() const {
    noise.validate();
    material.validate();
}

NoiseSurfaceEffect::NoiseSurfaceEffect(ClContext& cl, const NoiseSurfaceConfig& config)
    : Effect(validated(config).material), cl_(cl), config_(config) {
    setNoise(config.noise);
}

void NoiseSurfaceEffect::setNoise(const NoiseConfig& noise) {
    noise.validate();
    // Everything new is made before anything is replaced, so a failure keeps the old surface.
    const double time = noise_ ? noise_->time() : 0.0;
    auto field = std::make_unique<NoiseField>(cl_, noise);
    auto colors = std::make_unique<ColorRamp>(cl_, noise.width, noise.height, config_.palette);
    auto surface = std::make_unique<SurfacePipeline>(
        cl_, SurfacePipelineConfig::of(*field, config_.material.depthScale, config_.surface));
    if (surface_) clGuard("NoiseSurfaceEffect::setNoise", [&] { cl_.queue().finish(); }); // nothing in flight
    field->setTime(time);
    noise_ = std::move(field);
    colors_ = std::move(colors);
    surface_ = std::move(surface);
    config_.noise = noise;
    refresh();
}

void NoiseSurfaceEffect::setTime(double seconds) {
    noise_->setTime(seconds);
    refresh();
}

void NoiseSurfaceEffect::enqueueSurface() {
    surface_->derive(noise_->buffer());
    colors_->run(noise_->buffer());
    surface_->submit(&colors_->output());
}

} // namespace hfx
