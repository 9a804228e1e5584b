#include "hfx/effects/DecalWall.h"

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

struct WallMaps {
    int width = 0, height = 0;
    std::vector<float> heights;
    Image albedo;
    std::vector<float> normals; ///< packed float4 from the normal map, or empty
};

WallMaps loadWall(const DecalWallConfig& config) {
    config.validate();
    WallMaps maps;
    if (config.heightMap.empty()) {
        BrickWallMaps bricks = makeBrickWall(config.bricks);
        maps.width = maps.height = config.bricks.size;
        maps.heights = std::move(bricks.heights);
        maps.albedo = std::move(bricks.albedo);
        return maps;
    }
    const Image height = readImage(config.heightMap, config.limits);
    maps.width = height.width;
    maps.height = height.height;
    maps.heights = heightsFromImage(height, config.heightMap);
    if (!config.normalMap.empty())
        maps.normals = packNormalMap(readImage(config.normalMap, config.limits), config.normalMap, maps.heights);
    if (!config.colorMap.empty()) {
        maps.albedo = readImage(config.colorMap, config.limits);
        if (maps.albedo.width != height.width || maps.albedo.height != height.height)
            throw Error(str("colour map '", config.colorMap, "' is ", maps.albedo.width, "x", maps.albedo.height,
                            " but the height map '", config.heightMap, "' is ", height.width, "x", height.height));
    }
    return maps;
}

} // namespace

struct DecalWallEffect::Made {
    std::unique_ptr<HeightSource> source;
    Image albedo;
    std::vector<float> heights, normals; ///< kept only with a normal map
};

DecalWallEffect::Made DecalWallEffect::make(ClContext& cl, const DecalWallConfig& config) {
    WallMaps maps = loadWall(config);
    DecalConfig decals{.width = maps.width,
                       .height = maps.height,
                       .edges = EdgeMode::Wrap,
                       .healRate = config.healRate,
                       .maxStampsPerBatch = config.maxStampsPerBatch};
    Made made{std::make_unique<DecalMap>(cl, decals, maps.heights), std::move(maps.albedo), {}, {}};
    if (!maps.normals.empty()) {
        made.heights = std::move(maps.heights);
        made.normals = std::move(maps.normals);
    }
    return made;
}

namespace {

double wrap01(double x) {
    const double w = x - std::floor(x);
    return w >= 1.0 ? 0.0 : w;
}

} // namespace

DecalWallEffect::DecalWallEffect(ClContext& cl, const DecalWallConfig& config)
    : DecalWallEffect(cl, config, make(cl, config)) {}

DecalWallEffect::DecalWallEffect(ClContext& cl, const DecalWallConfig& config, Made made)
    : FieldEffect(cl, std::move(made.source), config.material,
                  config.surface), config_(config),
      decals_(static_cast<DecalMap&>(source())) {
    if (!made.albedo.empty()) setAlbedo(made.albedo);
    if (!made.normals.empty()) {
        baseHeights_ = std::move(made.heights);
        normalMap_ = std::move(made.normals);
        refresh(nowMs()); // again, now with the normal map
    }
}

void DecalWallEffect::enqueueExtra() {
    if (normalMap_.empty()) return;
    const SobelConfig& sobel = normals().config();
    if (!detail_ || detailDepth_ != sobel.depthScale) {
        detail_ = std::make_unique<DetailNormals>(cl(), sobel, baseHeights_, normalMap_);
        detailDepth_ = sobel.depthScale;
    }
    detail_->apply(normals().output());
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
        cl().queue().enqueueReadBuffer(decals_.buffer(), CL_TRUE, 0, heights.size() * sizeof(float), heights.data());
    });
    return heights;
}

std::optional<SurfacePick> DecalWallEffect::pick(const Ray& ray, const SurfaceFrame& frame) {
    const HeightFieldTracer tracer(readHeights(), decals_.width(), decals_.height(), EdgeMode::Wrap);
    return pickSurface(ray, frame, tracer, material().depthScale);
}

} // namespace hfx
