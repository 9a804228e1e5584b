#include "hfx/effects/WaterEffect.h"

#include "hfx/core/Error.h"
#include "hfx/effects/FieldUpload.h"

#include <chrono>

namespace hfx {
namespace {
double nowMs() {
    return std::chrono::duration<double, std::milli>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}
} // namespace

void WaterConfig::validate() const {
    waves.validate();
    material.validate();
}

WaterEffect::WaterEffect(ClContext& cl, const WaterConfig& config)
    : cl_(cl), config_((config.validate(), config)), waves_(cl, config.waves),
      normals_(cl, SobelConfig{.width = config.waves.size,
                               .height = config.waves.size,
                               .depthScale = config.material.depthScale,
                               .wrapEdges = true}),
      textures_(SurfaceTexturesConfig{.width = config.waves.size,
                                      .height = config.waves.size,
                                      .mipmaps = config.mipmaps,
                                      .edges = EdgeMode::Wrap}) {
    textures_.setAlbedo(Image{1, 1, 3, {0.05f, 0.22f, 0.30f}});
    refresh(nowMs());
}

void WaterEffect::update(double dt) {
    const double start = nowMs();
    waves_.step(dt);
    refresh(start);
}

void WaterEffect::setTime(double seconds) {
    const double start = nowMs();
    waves_.setTime(seconds);
    refresh(start);
}

void WaterEffect::refresh(double computeStartMs) {
    normals_.run(waves_.height());
    clGuard("WaterEffect::update", [&] { cl_.queue().finish(); });
    const double computed = nowMs();
    uploadField(cl_, normals_.output(), textures_);
    times_ = {computed - computeStartMs, nowMs() - computed};
}

} // namespace hfx
