#include "hfx/effects/DecalWallEffect.h"

#include "hfx/core/Error.h"
#include "hfx/core/SurfaceMaps.h"

#include <algorithm>
#include <cmath>

namespace hfx {

void DecalWallConfig::validate() const {
    if (maps) {
        if (maps->heights.empty())
            throw Error("DecalWallConfig.maps has no heights: colour and normal maps need a height map to go with "
                        "them (or no maps, for the procedural wall)");
        maps->validate();
    } else {
        bricks.validate();
    }
    damage.validate();
    if (!(grain >= 0.0f && grain <= 0.5f)) throw Error(str("DecalWallConfig.grain must be in [0, 0.5], got ", grain));
    if (!maps && grain > 0.0f) {
        NoiseConfig noise = grainNoise;
        noise.width = noise.height = bricks.size;
        noise.edges = EdgeMode::Wrap;
        noise.validate();
    }
    if (!(damage.look.bullet.radius > 0.0f) || !(damage.look.explosion.radius > 0.0f))
        throw Error(str("DecalWallConfig: bullet and explosion radii must be positive, got ", damage.look.bullet.radius,
                        " and ", damage.look.explosion.radius));
    const long long stamps = (long long)damage.budget * (1 + std::max(damage.look.explosion.debris, 0));
    if (stamps > maxStampsPerBatch)
        throw Error(str("DecalWallConfig: a budget of ", damage.budget, " impacts rebuilds up to ", stamps,
                        " stamps a frame (explosions with ", damage.look.explosion.debris,
                        " debris), more than maxStampsPerBatch = ", maxStampsPerBatch));
    material.validate();
}

namespace {

double wrap01(double x) {
    const double w = x - std::floor(x);
    return w >= 1.0 ? 0.0 : w;
}

/// RGBA8 bytes, row 0 at v = 0, of a colour image stored top row first; none for no image.
std::vector<std::uint8_t> albedoBytes(const Image& image) {
    std::vector<std::uint8_t> rgba;
    if (image.empty()) return rgba;
    rgba.resize(size_t(image.width) * image.height * 4);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 4; ++c) {
                const float v = c < 3 ? image.at(x, image.height - 1 - y, image.channels >= 3 ? c : 0)
                                      : (image.channels == 4 ? image.at(x, image.height - 1 - y, 3) : 1.0f);
                rgba[(size_t(y) * image.width + x) * 4 + c] = std::uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
            }
    return rgba;
}

} // namespace

SurfaceMaps DecalWallEffect::load(const DecalWallConfig& config) {
    config.validate();
    if (config.maps) return *config.maps;
    BrickWallMaps bricks = makeBrickWall(config.bricks);
    return {.width = config.bricks.size,
            .height = config.bricks.size,
            .heights = std::move(bricks.heights),
            .color = std::move(bricks.albedo)};
}

SurfaceMaps DecalWallEffect::withGrain(ClContext& cl, const DecalWallConfig& config, SurfaceMaps maps) {
    if (config.maps || config.grain == 0.0f) return maps;
    NoiseConfig noise = config.grainNoise;
    noise.width = maps.width;
    noise.height = maps.height;
    noise.edges = EdgeMode::Wrap; // the wall tiles
    NoiseField field(cl, noise);
    std::vector<float> grain(maps.heights.size());
    clGuard("reading the wall's grain", [&] {
        cl.queue().enqueueReadBuffer(field.buffer(), CL_TRUE, 0, grain.size() * sizeof(float), grain.data());
    });
    for (size_t i = 0; i < grain.size(); ++i)
        maps.heights[i] = std::clamp(maps.heights[i] + config.grain * (grain[i] - 0.5f), 0.0f, 1.0f);
    return maps;
}

DecalWallEffect::DecalWallEffect(ClContext& cl, const DecalWallConfig& config)
    : DecalWallEffect(cl, config, withGrain(cl, config, load(config))) {}

DecalWallEffect::DecalWallEffect(ClContext& cl, const DecalWallConfig& config, SurfaceMaps maps)
    : Effect(config.material), cl_(cl), config_(config), log_(config.damage),
      decals_(cl,
              {.width = maps.width,
               .height = maps.height,
               .edges = EdgeMode::Wrap,
               .maxStampsPerBatch = config.maxStampsPerBatch},
              maps.heights, albedoBytes(maps.color)),
      surface_(cl, SurfacePipelineConfig::of(decals_, config.material.depthScale, config.surface)) {
    if (!maps.normals.empty())
        detail_ = std::make_unique<DetailNormals>(cl, surface_.config().sobel(), maps.heights, maps.normals);
    config_.maps.reset(); // on the device now: no second copy of the maps for the effect's life
    refresh();
}

void DecalWallEffect::advance(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("DecalWallEffect::update: dt must be positive and finite, got ", dt));
    log_.advance(dt);
    if (log_.changes() != builtChanges_ || log_.healsBetween(builtClock_, log_.now())) rebuild();
}

void DecalWallEffect::rebuild() {
    decals_.addBulletHoles(log_.stamps());
    decals_.rebuild();
    builtChanges_ = log_.changes();
    builtClock_ = log_.now();
}

void DecalWallEffect::enqueueSurface() {
    surface_.derive(decals_.buffer());
    if (detail_) detail_->apply(surface_.normals());
    surface_.submit(&decals_.albedo(), &decals_.channels());
}

void DecalWallEffect::shoot(double u, double v) {
    if (!std::isfinite(u) || !std::isfinite(v))
        throw Error(str("DecalWallEffect::shoot: texcoords must be finite, got ", u, ", ", v));
    log_.add({.u = float(wrap01(u)), .v = float(wrap01(v)), .radius = config_.damage.look.bullet.radius,
              .kind = ImpactKind::Bullet, .seed = log_.added() + 1});
}

void DecalWallEffect::explode(double u, double v, std::uint64_t seed) {
    if (!std::isfinite(u) || !std::isfinite(v))
        throw Error(str("DecalWallEffect::explode: texcoords must be finite, got ", u, ", ", v));
    log_.add({.u = float(wrap01(u)), .v = float(wrap01(v)), .radius = config_.damage.look.explosion.radius,
              .kind = ImpactKind::Explosion, .seed = seed});
}

bool DecalWallEffect::impact(const ImpactEvent& impact) { return log_.add(impact); }

bool DecalWallEffect::impactAt(const ImpactEvent& impact, double time) { return log_.addAt(impact, time); }

void DecalWallEffect::loadDamage(const std::string& path) { replaceDamage(DamageLog::load(path, config_.damage)); }

void DecalWallEffect::loadDamage(std::istream& in, const std::string& name) {
    replaceDamage(DamageLog::load(in, config_.damage, name));
}

void DecalWallEffect::replaceDamage(DamageLog&& loaded) {
    log_ = std::move(loaded);
    rebuild();
    refresh();
}

void DecalWallEffect::impacts(const std::vector<ImpactEvent>& impacts) {
    DamageLog trial = log_; // all or none: a bad impact anywhere leaves the log as it was
    for (const ImpactEvent& e : impacts) trial.add(e);
    log_ = std::move(trial);
}

std::vector<float> DecalWallEffect::readHeights() {
    std::vector<float> heights(size_t(decals_.width()) * decals_.height());
    clGuard("reading the wall's heights", [&] {
        cl_.queue().enqueueReadBuffer(decals_.buffer(), CL_TRUE, 0, heights.size() * sizeof(float), heights.data());
    });
    return heights;
}

HeightFieldTracer DecalWallEffect::heightTracer() {
    return HeightFieldTracer(readHeights(), decals_.width(), decals_.height(), decals_.edges());
}

std::optional<SurfacePick> DecalWallEffect::pick(const Ray& ray, const SurfaceFrame& frame) {
    return pickSurface(ray, frame, heightTracer(), material().depthScale);
}

std::optional<MeshPick> DecalWallEffect::pick(const Ray& ray, const MeshData& mesh, const glm::mat4& model,
                                              const SurfaceMaterial& material,
                                              const std::optional<PixelNeighbours>& neighbours) {
    return pickMesh(ray, mesh, model, heightTracer(), material, neighbours);
}

} // namespace hfx
