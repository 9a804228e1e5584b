#include "hfx/effects/DecalWallEffect.h"

#include "hfx/core/Error.h"
#include "hfx/core/SurfaceMaps.h"

#include <cmath>

namespace hfx {

void DecalWallConfig::validate() const {
    if (heightMap.empty()) {
        bricks.validate();
        if (!colorMap.empty() || !normalMap.empty())
            throw Error(str("DecalWallConfig: a colour or normal map ('", colorMap.empty() ? normalMap : colorMap,
                            "') needs a heightMap to go with it"));
    }
    if (!(healRate >= 0.0f) || !std::isfinite(healRate))
        throw Error(str("DecalWallConfig.healRate must be >= 0 and finite, got ", healRate));
    if (!(bullet.radius > 0.0f) || !(explosion.radius > 0.0f))
        throw Error(str("DecalWallConfig: bullet and explosion radii must be positive, got ", bullet.radius,
                        " and ", explosion.radius));
    material.validate();
}

namespace {

double wrap01(double x) {
    const double w = x - std::floor(x);
    return w >= 1.0 ? 0.0 : w;
}

} // namespace

SurfaceMaps DecalWallEffect::load(const DecalWallConfig& config) {
    config.validate();
    if (!config.heightMap.empty())
        return readSurfaceMaps(config.heightMap, config.normalMap, config.colorMap, config.limits);
    BrickWallMaps bricks = makeBrickWall(config.bricks);
    return {.width = config.bricks.size,
            .height = config.bricks.size,
            .heights = std::move(bricks.heights),
            .color = std::move(bricks.albedo)};
}

DecalWallEffect::DecalWallEffect(ClContext& cl, const DecalWallConfig& config)
    : DecalWallEffect(cl, config, load(config)) {}

DecalWallEffect::DecalWallEffect(ClContext& cl, const DecalWallConfig& config, SurfaceMaps maps)
    : Effect(config.material), cl_(cl), config_(config),
      decals_(cl,
              {.width = maps.width,
               .height = maps.height,
               .edges = EdgeMode::Wrap,
               .healRate = config.healRate,
               .maxStampsPerBatch = config.maxStampsPerBatch},
              maps.heights),
      surface_(cl, SurfacePipelineConfig::of(decals_, config.material.depthScale, config.surface)) {
    if (!maps.color.empty()) surface_.setAlbedo(maps.color);
    if (!maps.normals.empty())
        detail_ = std::make_unique<DetailNormals>(cl, surface_.config().sobel(), maps.heights, maps.normals);
    refresh();
}

void DecalWallEffect::enqueueSurface() {
    surface_.derive(decals_.buffer());
    if (detail_) detail_->apply(surface_.normals());
    surface_.submit();
}

void DecalWallEffect::shoot(double u, double v) {
    if (!std::isfinite(u) || !std::isfinite(v))
        throw Error(str("DecalWallEffect::shoot: texcoords must be finite, got ", u, ", ", v));
    BulletHole hole = config_.bullet;
    hole.u = float(wrap01(u));
    hole.v = float(wrap01(v));
    decals_.addBulletHole(hole);
}

void DecalWallEffect::explode(double u, double v, std::uint64_t seed) {
    if (!std::isfinite(u) || !std::isfinite(v))
        throw Error(str("DecalWallEffect::explode: texcoords must be finite, got ", u, ", ", v));
    Explosion e = config_.explosion;
    e.u = float(wrap01(u));
    e.v = float(wrap01(v));
    e.seed = seed;
    decals_.addExplosion(e);
}

std::vector<float> DecalWallEffect::readHeights() {
    std::vector<float> heights(size_t(decals_.width()) * decals_.height());
    clGuard("reading the wall's heights", [&] {
        cl_.queue().enqueueReadBuffer(decals_.buffer(), CL_TRUE, 0, heights.size() * sizeof(float), heights.data());
    });
    return heights;
}

std::optional<SurfacePick> DecalWallEffect::pick(const Ray& ray, const SurfaceFrame& frame) {
    const HeightFieldTracer tracer(readHeights(), decals_.width(), decals_.height(), decals_.edges());
    return pickSurface(ray, frame, tracer, material().depthScale);
}

} // namespace hfx
