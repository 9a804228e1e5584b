#include "hfx/compute/DecalMap.h"

#include "hfx/compute/shared/DecalMath.h"
#include "hfx/core/Error.h"
#include "hfx/core/Random.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hfx {

void DecalConfig::validate() const {
    if (width < 2 || height < 2 || width > 16384 || height > 16384)
        throw Error(str("DecalConfig size must be in 2..16384, got ", width, "x", height));
    if (!(healRate >= 0.0f) || !std::isfinite(healRate))
        throw Error(str("DecalConfig.healRate must be >= 0 and finite, got ", healRate));
    if (tileSize < 4 || tileSize > 256)
        throw Error(str("DecalConfig.tileSize must be in [4, 256], got ", tileSize));
    if (maxStampsPerBatch < 1 || maxStampsPerBatch > (1 << 22))
        throw Error(str("DecalConfig.maxStampsPerBatch must be in [1, 4194304], got ", maxStampsPerBatch));
    if (!(baseHeight >= 0.0f && baseHeight <= 1.0f))
        throw Error(str("DecalConfig.baseHeight must be in [0, 1], got ", baseHeight));
    for (float c : soot)
        if (!(c >= 0.0f && c <= 1.0f))
            throw Error(str("DecalConfig.soot components must be in [0, 1], got ", c));
}

DecalMap::DecalMap(ClContext& cl, const DecalConfig& config, const std::vector<float>& base,
                   const std::vector<std::uint8_t>& baseAlbedo)
    : cl_(cl), config_((config.validate(), config)),
      tilesX_((config.width + config.tileSize - 1) / config.tileSize),
      tilesY_((config.height + config.tileSize - 1) / config.tileSize) {
    const size_t texels = size_t(config.width) * config.height;
    std::vector<float> baseHeights = base.empty() ? std::vector<float>(texels, config.baseHeight) : base;
    if (baseHeights.size() != texels)
        throw Error(str("DecalMap: the base map has ", base.size(), " heights, the ", config.width, "x",
                        config.height, " map needs ", texels));
    for (size_t i = 0; i < texels; ++i)
        if (!(baseHeights[i] >= 0.0f && baseHeights[i] <= 1.0f))
            throw Error(str("DecalMap: base height ", baseHeights[i], " at texel ", i % config.width, ",",
                            i / config.width, " is outside [0, 1]"));
    std::vector<std::uint8_t> albedo = baseAlbedo;
    if (albedo.empty()) albedo.assign(4 * texels, 204);
    if (albedo.size() != 4 * texels)
        throw Error(str("DecalMap: the base albedo has ", baseAlbedo.size(), " bytes, the ", config.width, "x",
                        config.height, " map needs ", 4 * texels, " (RGBA8)"));
    tileStart_.resize(size_t(tilesX_) * tilesY_ + 1);
    tileCounts_.resize(size_t(tilesX_) * tilesY_);
    clGuard("creating the decal map", [&] {
        base_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, texels * sizeof(float),
                           baseHeights.data());
        damage_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, texels * sizeof(float));
        height_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, texels * sizeof(float));
        tileStartBuffer_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY, tileStart_.size() * sizeof(int));
        baseAlbedo_ = cl::Buffer(cl.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, albedo.size(), albedo.data());
        albedo_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, albedo.size());
        channels_ = cl::Buffer(cl.context(), CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, albedo.size());
        kernel_ = cl.kernel("decals.cl", "decals",
                            str("-DTILE=", config.tileSize, " ", edgeOptions(config.edges)));
    });
    clear();
}

void DecalMap::clear() {
    pending_.clear();
    clGuard("clearing the decal map", [&] {
        cl_.queue().enqueueFillBuffer(damage_, 0.0f, 0, sizeof(float) * size_t(config_.width) * config_.height);
    });
    step(1.0); // writes the combined height; nothing to heal yet
}

void DecalMap::validate(const BulletHole& h) const {
    if (!(h.u >= 0.0f && h.u < 1.0f && h.v >= 0.0f && h.v < 1.0f))
        throw Error(str("decal at (", h.u, ", ", h.v, ") is outside the map: texcoords must lie in [0, 1)"));
    if (!(h.radius > 0.0f) || h.radius > 1.0f)
        throw Error(str("decal radius must be in (0, 1] map widths, got ", h.radius));
    if (!(h.depth >= 0.0f && h.depth <= 1.0f))
        throw Error(str("decal depth must be in [0, 1], got ", h.depth));
    if (!(h.rimHeight >= 0.0f && h.rimHeight <= 1.0f))
        throw Error(str("decal rimHeight must be in [0, 1], got ", h.rimHeight));
    if (!(h.rimWidth > 0.0f && h.rimWidth <= 4.0f))
        throw Error(str("decal rimWidth must be in (0, 4] radii, got ", h.rimWidth));
    for (auto [value, name] : {std::pair{h.scorch, "scorch"}, std::pair{h.roughness, "roughness"},
                               std::pair{h.occlusion, "occlusion"}, std::pair{h.glow, "glow"}})
        if (!(value >= 0.0f && value <= 1.0f)) throw Error(str("decal ", name, " must be in [0, 1], got ", value));
    if (!(h.scorchReach >= 1.0f && h.scorchReach <= 16.0f))
        throw Error(str("decal scorchReach must be in [1, 16] radii, got ", h.scorchReach));
    if (!std::isfinite(h.phase)) throw Error(str("decal phase must be finite, got ", h.phase));
}

void DecalMap::addBulletHole(const BulletHole& hole) { addBulletHoles({hole}); }

void DecalMap::addBulletHoles(const std::vector<BulletHole>& holes) {
    for (const BulletHole& h : holes) validate(h);
    if (pending_.size() + holes.size() > size_t(config_.maxStampsPerBatch))
        throw Error(str("decal batch of ", pending_.size() + holes.size(), " stamps exceeds maxStampsPerBatch = ",
                        config_.maxStampsPerBatch, "; step() between batches"));
    pending_.insert(pending_.end(), holes.begin(), holes.end());
}

std::vector<BulletHole> DecalMap::expand(const Explosion& e, EdgeMode edges) {
    if (e.debris < 0 || e.debris > 4096)
        throw Error(str("explosion debris count must be in [0, 4096], got ", e.debris));
    if (!(e.debrisSpread >= 1.0f && e.debrisSpread <= 16.0f))
        throw Error(str("explosion debrisSpread must be in [1, 16], got ", e.debrisSpread));
    std::vector<BulletHole> stamps;
    SplitMix64 random(e.seed);
    stamps.push_back({e.u, e.v, e.radius, e.depth, e.depth * 0.25f, 0.3f, e.scorch, e.roughness, e.occlusion,
                      e.scorchReach, float(random.uniform(0.0, 2.0 * std::numbers::pi)), e.glow});
    for (int i = 0; i < e.debris; ++i) {
        const double angle = random.uniform(0.0, 2.0 * std::numbers::pi);
        const double distance = e.radius * random.uniform(0.6, e.debrisSpread);
        float u = float(e.u + distance * std::cos(angle)), v = float(e.v + distance * std::sin(angle));
        const float size = float(e.debrisRadius * random.uniform(0.5, 1.5));
        const float depth = float(e.depth * random.uniform(0.2, 0.5));
        // Across an edge that wraps the debris lands on the other side; past one that clamps it
        // flew off the map.
        auto land = [](float& x, bool wraps) {
            if (wraps) x = std::min(x - std::floor(x), std::nextafter(1.0f, 0.0f));
            return x >= 0.0f && x < 1.0f;
        };
        if (!land(u, wrapsU(edges)) || !land(v, wrapsV(edges))) continue;
        stamps.push_back({u, v, size, depth, depth * 0.3f, 0.4f, 0.5f * e.scorch, 0.5f * e.roughness, 0.5f * e.occlusion,
                          1.5f, float(angle), 0.5f * e.glow});
    }
    return stamps;
}

void DecalMap::addExplosion(const Explosion& explosion) {
    addBulletHoles(expand(explosion, config_.edges));
}

void DecalMap::bin() {
    const int W = config_.width, H = config_.height, T = config_.tileSize;
    std::fill(tileCounts_.begin(), tileCounts_.end(), 0);
    stamps_.clear();
    shapes_.clear();
    looks_.clear();
    wobbles_.clear();
    tileStamps_.clear();
    // The tiles a stamp's footprint covers, per axis as at most two ranges of tiles: along an
    // axis that wraps the texel range wraps (texels carry the period, and the last tile may be
    // partial, so wrapping is done on texels, then mapped to tiles).
    struct Range {
        int lo, hi;
    };
    auto axis = [&](double centre, double reach, int n, int tiles, bool wraps, Range* out) -> int {
        int a = int(std::floor(centre - reach)), b = int(std::floor(centre + reach));
        if (!wraps) {
            a = std::max(a, 0), b = std::min(b, n - 1);
            if (a > b) return 0;
            out[0] = {a / T, b / T};
            return 1;
        }
        if (b - a + 1 >= n) return out[0] = {0, tiles - 1}, 1;
        const int wa = ((a % n) + n) % n, wb = ((b % n) + n) % n;
        if (wa <= wb) return out[0] = {wa / T, wb / T}, 1;
        if (wb / T >= wa / T) return out[0] = {0, tiles - 1}, 1; // the two pieces share a tile
        out[0] = {wa / T, tiles - 1};
        out[1] = {0, wb / T};
        return 2;
    };
    auto forEachTile = [&](const BulletHole& h, auto&& visit) {
        const double reach = h.radius * hfx_decal_reach(h.rimWidth, h.scorch, h.roughness, h.scorchReach) * W + 1.0;
        Range xs[2], ys[2];
        const int nx = axis(h.u * W, reach, W, tilesX_, wrapsU(config_.edges), xs),
                  ny = axis(h.v * H, reach, H, tilesY_, wrapsV(config_.edges), ys);
        for (int i = 0; i < ny; ++i)
            for (int ty = ys[i].lo; ty <= ys[i].hi; ++ty)
                for (int j = 0; j < nx; ++j)
                    for (int tx = xs[j].lo; tx <= xs[j].hi; ++tx) visit(ty * tilesX_ + tx);
    };
    for (const BulletHole& h : pending_) forEachTile(h, [&](int tile) { ++tileCounts_[tile]; });
    tileStart_[0] = 0;
    for (size_t t = 0; t < tileCounts_.size(); ++t) tileStart_[t + 1] = tileStart_[t] + tileCounts_[t];
    tileStamps_.resize(size_t(tileStart_.back()));
    std::fill(tileCounts_.begin(), tileCounts_.end(), 0);
    for (size_t i = 0; i < pending_.size(); ++i) {
        const BulletHole& h = pending_[i];
        const float radius = h.radius * float(W);
        const float reach = radius * hfx_decal_reach(h.rimWidth, h.scorch, h.roughness, h.scorchReach);
        stamps_.push_back({{h.u * float(W), h.v * float(H), 1.0f / radius, h.depth}});
        shapes_.push_back({{h.rimHeight, h.rimWidth, reach * reach, h.glow}});
        looks_.push_back({{h.scorch, h.roughness, h.occlusion, h.scorchReach}});
        cl_float4 wobble;
        hfx_decal_wobble(h.phase, wobble.s);
        wobbles_.push_back(wobble);
        forEachTile(h, [&](int tile) { tileStamps_[size_t(tileStart_[tile] + tileCounts_[tile]++)] = int(i); });
    }
}

void DecalMap::step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw Error(str("DecalMap::step: dt must be positive and finite, got ", dt));
    apply(float(std::exp(-double(config_.healRate) * dt)));
}

void DecalMap::rebuild() { apply(0.0f); }

void DecalMap::apply(float heal) {
    bin();
    clGuard("DecalMap::step", [&] {
        cl::CommandQueue& q = cl_.queue();
        // Grow-only device buffers; at least one element so the kernel always has valid args.
        if (stamps_.size() > stampCapacity_ || !stampBuffer_()) {
            stampCapacity_ = std::max<size_t>(stamps_.size(), 256);
            stampBuffer_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY, stampCapacity_ * sizeof(cl_float4));
            shapeBuffer_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY, stampCapacity_ * sizeof(cl_float4));
            lookBuffer_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY, stampCapacity_ * sizeof(cl_float4));
            wobbleBuffer_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY, stampCapacity_ * sizeof(cl_float4));
        }
        if (tileStamps_.size() > listCapacity_ || !tileStampsBuffer_()) {
            listCapacity_ = std::max<size_t>(tileStamps_.size(), 1024);
            tileStampsBuffer_ = cl::Buffer(cl_.context(), CL_MEM_READ_ONLY, listCapacity_ * sizeof(int));
        }
        // Blocking writes: the staging vectors are rebuilt by the next step.
        q.enqueueWriteBuffer(tileStartBuffer_, CL_TRUE, 0, tileStart_.size() * sizeof(int), tileStart_.data());
        if (!stamps_.empty()) {
            q.enqueueWriteBuffer(stampBuffer_, CL_TRUE, 0, stamps_.size() * sizeof(cl_float4), stamps_.data());
            q.enqueueWriteBuffer(shapeBuffer_, CL_TRUE, 0, shapes_.size() * sizeof(cl_float4), shapes_.data());
            q.enqueueWriteBuffer(lookBuffer_, CL_TRUE, 0, looks_.size() * sizeof(cl_float4), looks_.data());
            q.enqueueWriteBuffer(wobbleBuffer_, CL_TRUE, 0, wobbles_.size() * sizeof(cl_float4), wobbles_.data());
            q.enqueueWriteBuffer(tileStampsBuffer_, CL_TRUE, 0, tileStamps_.size() * sizeof(int), tileStamps_.data());
        }
        int a = 0;
        kernel_.setArg(a++, damage_);
        kernel_.setArg(a++, base_);
        kernel_.setArg(a++, height_);
        kernel_.setArg(a++, config_.width);
        kernel_.setArg(a++, config_.height);
        kernel_.setArg(a++, heal);
        kernel_.setArg(a++, tilesX_);
        kernel_.setArg(a++, tileStartBuffer_);
        kernel_.setArg(a++, tileStampsBuffer_);
        kernel_.setArg(a++, stampBuffer_);
        kernel_.setArg(a++, shapeBuffer_);
        kernel_.setArg(a++, lookBuffer_);
        kernel_.setArg(a++, wobbleBuffer_);
        kernel_.setArg(a++, baseAlbedo_);
        kernel_.setArg(a++, albedo_);
        kernel_.setArg(a++, channels_);
        kernel_.setArg(a++, cl_float4{{255.0f * config_.soot[0], 255.0f * config_.soot[1], 255.0f * config_.soot[2], 255.0f}});
        // One work-group per tile: every work-item of a group loops over the same stamp list,
        // so the device can run the group's loop in vector lanes.
        const size_t T = size_t(config_.tileSize);
        cl_.enqueue(kernel_, cl::NDRange(tilesX_ * T, tilesY_ * T), cl::NDRange(T, T));
    });
    pending_.clear();
}

} // namespace hfx
