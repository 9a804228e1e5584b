#pragma once
// A persistent damage map: bullet holes (craters with raised rims) and explosions (a large
// crater plus scattered debris pits) stamped in batches of thousands, on top of a base height
// map (a brick wall, say). Damage accumulates but base + damage never leaves [0,1]; it may heal
// slowly. Stamps wrap across the edges that wrap (DecalConfig::edges).
//
// Positions are texcoords in [0,1); radii are in units of the map's width.
// Thread: the thread that owns the ClContext.

#include "hfx/compute/HeightSource.h"

#include <array>
#include <cstdint>
#include <vector>

namespace hfx {

struct BulletHole {
    float u = 0.5f, v = 0.5f;
    float radius = 0.01f;
    float depth = 0.35f;     ///< of the bowl at its centre, height units
    float rimHeight = 0.08f; ///< raised lip, height units
    float rimWidth = 0.35f;  ///< half-width of the lip, in radii
    // Shading marks (DecalMath.h, hfx_decal_marks), each 0 (none) to 1:
    float scorch = 0.0f;      ///< soot burnt into the albedo, out to scorchReach radii
    float roughness = 0.0f;   ///< the fresh fracture's roughness over the bowl and lip
    float occlusion = 0.0f;   ///< how dark the bowl's floor is to ambient light
    float scorchReach = 2.0f; ///< radii, 1 to 16
    float phase = 0.0f;       ///< turns the scorch's ragged edge (radians)
    float glow = 0.0f;        ///< a fresh crater's heat, glowing in cracks (hfx_decal_heat, hfx_decal_crust)
};

struct Explosion {
    float u = 0.5f, v = 0.5f;
    float radius = 0.06f;
    float depth = 0.6f;
    int debris = 24;              ///< small pits scattered around the crater
    float debrisRadius = 0.006f;
    float debrisSpread = 2.5f;    ///< debris lands up to this many crater radii out
    std::uint64_t seed = 1;       ///< where the debris lands, and the scorch's edge
    float scorch = 0.0f;          ///< the crater's marks (BulletHole's); the debris get half
    float roughness = 0.0f;
    float occlusion = 0.0f;
    float scorchReach = 2.5f;
    float glow = 0.0f;            ///< the crater's heat (BulletHole::glow); the debris get half
};

struct DecalConfig {
    int width = 512;
    int height = 512;
    EdgeMode edges = EdgeMode::Wrap; ///< stamps wrap across the edges that wrap (tileable walls)
    float healRate = 0.0f;         ///< damage decays as exp(-healRate t); 0 = permanent
    int tileSize = 16;             ///< texels per binning tile edge
    int maxStampsPerBatch = 65536; ///< a larger batch is refused, not truncated
    float baseHeight = 0.85f;      ///< flat base when no base map is given
    std::array<float, 3> soot{0.05f, 0.045f, 0.04f}; ///< linear RGB the scorch burns the albedo towards
    void validate() const;
};

class DecalMap final : public HeightSource {
public:
    /// base: width*height heights in [0,1], row 0 at v = 0; empty: flat at config.baseHeight.
    /// baseAlbedo: width*height RGBA8, row 0 at v = 0; empty: light grey.
    DecalMap(ClContext& cl, const DecalConfig& config, const std::vector<float>& base = {},
             const std::vector<std::uint8_t>& baseAlbedo = {});

    /// Queue stamps for the next step(). Throws hfx::Error and queues nothing when the stamp is
    /// outside the map, has a non-positive radius, a negative depth or overflows the batch.
    void addBulletHole(const BulletHole& hole);
    void addBulletHoles(const std::vector<BulletHole>& holes); ///< all or nothing
    void addExplosion(const Explosion& explosion);
    size_t pendingStamps() const { return pending_.size(); }

    /// Heals by dt, applies the queued stamps, writes the combined height; does not wait.
    /// The albedo and the shading channels carry the marks of this step's stamps only.
    void step(double dt) override;
    /// Replaces all damage with the queued stamps alone (a map made from a DamageLog each frame).
    void rebuild();
    /// Forgets all damage.
    void clear();

    const cl::Buffer& buffer() const override { return height_; }
    const cl::Buffer& damage() const { return damage_; }
    /// RGBA8, row 0 at v = 0: the base albedo burnt by the last step's scorch.
    const cl::Buffer& albedo() const { return albedo_; }
    /// RGBA8 shading channels of the last step (SurfaceTextures::uploadChannels): roughness,
    /// occlusion, scorch, glow.
    const cl::Buffer& channels() const { return channels_; }
    int width() const override { return config_.width; }
    int height() const override { return config_.height; }
    EdgeMode edges() const override { return config_.edges; }
    const DecalConfig& config() const { return config_; }

    /// The stamps an explosion expands into: the crater first, then the debris pits.
    /// Debris past an edge that wraps lands across it; past one that clamps it is dropped.
    static std::vector<BulletHole> expand(const Explosion& explosion, EdgeMode edges);

private:
    void validate(const BulletHole& hole) const;
    void bin();
    void apply(float heal);

    ClContext& cl_;
    DecalConfig config_;
    int tilesX_, tilesY_;
    std::vector<BulletHole> pending_;
    // Staging reused every step: stamps, shapes and the tile lists.
    std::vector<cl_float4> stamps_;
    std::vector<cl_float4> shapes_;
    std::vector<cl_float4> looks_, wobbles_;
    std::vector<int> tileStart_, tileStamps_, tileCounts_;
    size_t stampCapacity_ = 0, listCapacity_ = 0;
    cl::Buffer base_, damage_, height_, tileStartBuffer_, tileStampsBuffer_, stampBuffer_, shapeBuffer_, lookBuffer_, wobbleBuffer_;
    cl::Buffer baseAlbedo_, albedo_, channels_;
    cl::Kernel kernel_;
};

} // namespace hfx
