#pragma once
// The decal-damage user: a wall (height and colour maps from files, or a procedural brick wall
// when none are given) carrying a persistent DecalMap. Shots and explosions are queued by
// texcoord and stamped on the device in the next update(); pick() turns a camera ray into the
// texcoord the user sees on the displaced surface. Normals are re-derived from the damaged
// heights every update (and added to the normal map's, when one is given), so craters shade,
// cast soft self-shadows and clip geometry (POM's depth output) from the frame they appear in.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/DecalMap.h"
#include "hfx/compute/DetailNormals.h"
#include "hfx/core/SurfaceMaps.h"
#include "hfx/effects/BrickWall.h"
#include "hfx/effects/Effect.h"
#include "hfx/effects/Picking.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hfx {

struct DecalWallConfig {
    std::string heightMap;      ///< optional: a procedural brick wall when empty
    std::string colorMap;       ///< optional: with a height map, light grey when empty
    /// optional, with a height map: the artist's tangent-space normals (OpenGL convention). The
    /// damage's relief is added to them in slope space each update, so undamaged texels show
    /// the map exactly and craters bend it.
    std::string normalMap;
    BrickWallConfig bricks;     ///< the procedural wall (its size sets the map's)
    float healRate = 0.0f;      ///< damage decays as exp(-healRate t); 0 = permanent
    int maxStampsPerBatch = 65536;
    BulletHole bullet{.radius = 0.012f, .depth = 0.5f, .rimHeight = 0.08f};
    Explosion explosion{.radius = 0.05f, .depth = 0.6f, .debris = 40};
    SurfaceMaterial material{.depthScale = 0.06f, .maxSamples = 48, .shadowSharpness = 3.0f};
    ImageReadLimits limits;
    SurfaceOptions surface; ///< mip maps, height pyramid, storage format, path to GL
    void validate() const;  ///< throws hfx::Error naming the bad field and its value
};

class DecalWallEffect final : public Effect {
public:
    /// Throws hfx::Error naming the file for a missing, corrupt or mismatched map.
    DecalWallEffect(ClContext& cl, const DecalWallConfig& config = {});

    /// Queues a bullet hole (the configured shape) at texcoords wrapped into [0,1).
    void shoot(double u, double v);
    /// Queues an explosion at texcoords wrapped into [0,1); `seed` scatters its debris.
    void explode(double u, double v, std::uint64_t seed);
    DecalMap& decals() { return decals_; }
    const DecalWallConfig& config() const { return config_; }

    /// The texcoords a world ray meets on the displaced wall drawn on `frame`, using the heights
    /// of the last update (read back once per call).
    std::optional<SurfacePick> pick(const Ray& ray, const SurfaceFrame& frame);
    /// The combined heights of the last update, row 0 at v = 0 (for picking and export).
    std::vector<float> readHeights();

private:
    /// The wall's maps (files, or the procedural bricks), made before anything on a device.
    static SurfaceMaps load(const DecalWallConfig& config);
    DecalWallEffect(ClContext& cl, const DecalWallConfig& config, SurfaceMaps maps);
    const SurfacePipeline& surface() const override { return surface_; }
    void advance(double dt) override { decals_.step(dt); }
    /// The damaged heights' normals, with the artist's normal map added when there is one.
    void enqueueSurface() override;

    ClContext& cl_;
    DecalWallConfig config_;
    DecalMap decals_;
    SurfacePipeline surface_;
    std::unique_ptr<DetailNormals> detail_; ///< with a normal map
};

} // namespace hfx
