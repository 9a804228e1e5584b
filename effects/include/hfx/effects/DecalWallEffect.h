#pragma once
// The decal-damage user: a wall (height and colour maps of the caller's, or a procedural brick
// wall when none are given) carrying damage a game can ship: a DamageLog of impacts (a fixed budget,
// oldest evicted first, close impacts merged, heal curves per channel, save and load), from
// which the DecalMap rebuilds the heights, the scorched albedo and the shading channels
// (roughness, ambient occlusion, a fresh crater's glow) every update. pick() turns a camera ray
// into the texcoord the user sees on the displaced surface. Normals are re-derived from the
// damaged heights every update (and added to the normal map's, when one is given), so craters
// shade, cast soft self-shadows and clip geometry (POM's depth output) from the frame they
// appear in.
//
// Thread: the thread that owns both the ClContext and the current GL context.

#include "hfx/compute/DamageLog.h"
#include "hfx/compute/DecalMap.h"
#include "hfx/compute/NoiseField.h"
#include "hfx/compute/DetailNormals.h"
#include "hfx/core/SurfaceMaps.h"
#include "hfx/effects/BrickWall.h"
#include "hfx/effects/Effect.h"
#include "hfx/effects/Picking.h"

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hfx {

struct DecalWallConfig {
    /// The wall's maps (the tools' readSurfaceMaps reads them from files); none: a procedural
    /// brick wall. Their colour is light grey when empty; their normals, when given, are the
    /// artist's tangent-space normals (OpenGL convention): the damage's relief is added to them
    /// in slope space each update, so undamaged texels show the map exactly and craters bend it.
    std::optional<SurfaceMaps> maps;
    BrickWallConfig bricks;     ///< the procedural wall (its size sets the map's)
    /// The procedural wall's stone grain: a NoiseField (made once on the device; its size and
    /// tiling are the wall's) added to the bricks' heights, grain * (noise - 0.5). 0: none.
    float grain = 0.06f;
    NoiseConfig grainNoise{.kind = NoiseKind::Perlin, .fractal = Fractal::Turbulence, .frequency = 32.0f,
                           .octaves = 3, .gain = 0.55f, .speed = 0.0f};
    /// The impacts' budget, merging, look (shapes and marks) and heal curves.
    DamageLogConfig damage;
    int maxStampsPerBatch = 65536; ///< stamps per rebuild: the budget's impacts with their debris
    SurfaceMaterial material{.depthScale = 0.06f, .maxSamples = 48, .shadowSharpness = 3.0f};
    SurfaceOptions surface; ///< mip maps, storage format, path to GL
    void validate() const;  ///< throws hfx::Error naming the bad field and its value
};

class DecalWallEffect final : public Effect {
public:
    /// Throws hfx::Error naming the field for mismatched or out-of-range maps.
    DecalWallEffect(ClContext& cl, const DecalWallConfig& config = {});

    /// A bullet hole (the look's radius) at texcoords wrapped into [0,1), in the next update.
    void shoot(double u, double v);
    /// An explosion at texcoords wrapped into [0,1); `seed` scatters its debris.
    void explode(double u, double v, std::uint64_t seed);
    /// Any impact (DamageLog::add: merged, or evicting the oldest); true when it merged.
    bool impact(const ImpactEvent& impact);
    /// A peer's impact made at `time` on the log's clock (DamageLog::addAt: a client adding a
    /// server's impacts, in its order, draws the server's wall; damage().now() is the clock,
    /// which update(dt) moves).
    bool impactAt(const ImpactEvent& impact, double time);
    /// Several impacts, all or none: every one is checked before any is added.
    void impacts(const std::vector<ImpactEvent>& impacts);
    /// Forgets all damage (the next update shows the bare wall).
    void clearDamage() { log_.clear(); }
    const DamageLog& damage() const { return log_; }
    /// Writes the damage (DamageLog::save); loadDamage replaces it with a saved one and redraws
    /// the surface from it at once, exactly as the run that saved it drew it. Throws naming the
    /// file; a failed load keeps the damage there was.
    void saveDamage(const std::string& path) const { log_.save(path); }
    void loadDamage(const std::string& path);
    /// The same through streams (a server's snapshot sent to a client joining late: a string
    /// stream); `name` says what the stream is in an error.
    void saveDamage(std::ostream& out, const std::string& name = "a stream") const { log_.save(out, name); }
    void loadDamage(std::istream& in, const std::string& name = "a stream");
    const DecalMap& decals() const { return decals_; }
    /// The configuration it was made with, less its maps (they live on the device).
    const DecalWallConfig& config() const { return config_; }

    /// The texcoords a world ray meets on the displaced wall drawn on `frame`, using the heights
    /// of the last update (read back once per call).
    std::optional<SurfacePick> pick(const Ray& ray, const SurfaceFrame& frame);
    /// ... on the wall drawn on any `mesh` (a pillar, a barrel, a triplanar rock) with `model`
    /// and `material` (pickMesh; with the pixel's `neighbours`, at the draw's level of detail):
    /// shoot(pick->uv) stamps where the ray met the relief.
    std::optional<MeshPick> pick(const Ray& ray, const MeshData& mesh, const glm::mat4& model,
                                 const SurfaceMaterial& material,
                                 const std::optional<PixelNeighbours>& neighbours = std::nullopt);
    /// The combined heights of the last update, row 0 at v = 0 (for picking and export).
    std::vector<float> readHeights();
    /// Those heights' exact tracer, for pickSurface and pickMesh (read back once per call).
    HeightFieldTracer heightTracer();

private:
    /// The wall's maps (the caller's, or the procedural bricks), made before anything on a device.
    static SurfaceMaps load(const DecalWallConfig& config);
    /// The procedural wall's heights with the stone grain added (the caller's are kept as they are).
    static SurfaceMaps withGrain(ClContext& cl, const DecalWallConfig& config, SurfaceMaps maps);
    DecalWallEffect(ClContext& cl, const DecalWallConfig& config, SurfaceMaps maps);
    /// loadDamage's second half: the log taken, the maps rebuilt and drawn from it.
    void replaceDamage(DamageLog&& loaded);
    const SurfacePipeline& surface() const override { return surface_; }
    /// Moves the log's clock and rebuilds the maps from it when they would change: an impact
    /// came, merged or went, or a heal curve moved (the decal pass costs what the budget's
    /// stamps cover; a still wall costs nothing).
    void advance(double dt) override;
    void rebuild();
    /// The damaged heights' normals, with the artist's normal map added when there is one.
    void enqueueSurface() override;

    ClContext& cl_;
    DecalWallConfig config_;
    DamageLog log_;
    std::uint64_t builtChanges_ = ~0ull; ///< the log's changes() and clock the maps show
    double builtClock_ = 0.0;
    DecalMap decals_;
    SurfacePipeline surface_;
    std::unique_ptr<DetailNormals> detail_; ///< with a normal map
};

} // namespace hfx
