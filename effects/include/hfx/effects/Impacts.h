#pragma once
// One impact API across every surface: a bullet or a blast travels along a ray from a world
// point, and the first surface on its path takes it, found by the exact pick of the surface as
// drawn (the bilinear ray/height-field intersection on the wall and the planet, the CPU ocean
// query on the water). What it does depends on what it hits: the wall is dented, scorched and
// logged (DecalWallEffect, DamageLog), the ocean rings with waves and foam
// (OceanEffect::disturb), the gas giant spins up a storm (GasPlanetEffect::addStorm).
//
//   WallImpacts wall(decalWall, SurfaceFrame::ofPlane(plane, model)); // or (decalWall, meshData, model)
//   OceanImpacts sea(ocean, SurfaceFrame::ofPlane(seaPlane));
//   ImpactReceiver* targets[] = {&wall, &sea};
//   if (auto hit = routeImpact({.origin = gun, .direction = aim}, targets)) ... // who took it, where
//
// Thread: the thread that owns the effects' ClContext and GL context (picking reads back).

#include "hfx/compute/DamageLog.h"
#include "hfx/compute/OceanQuery.h"
#include "hfx/core/Camera.h"
#include "hfx/core/Mesh.h"
#include "hfx/effects/Picking.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>

namespace hfx {

class DecalWallEffect;
class OceanEffect;
class GasPlanetEffect;

struct Impact {
    glm::dvec3 origin{0.0};            ///< where it comes from (world)
    glm::dvec3 direction{0.0, 0.0, -1.0}; ///< its path, any length > 0
    float energy = 1.0f;               ///< 1: the kind's usual; sizes grow with its cube root
    ImpactKind kind = ImpactKind::Bullet;
    std::uint64_t seed = 1;            ///< debris, the scorch's outline, a storm's spin
    void validate() const;             ///< throws hfx::Error naming the bad field
};

struct ImpactHit {
    glm::dvec3 world{0.0};  ///< the point on the surface as drawn
    glm::dvec2 uv{0.0};     ///< the surface's texcoords there (the mesh's)
    glm::dvec3 normal{0.0}; ///< the surface's unit normal there (world)
    double distance = 0.0;  ///< from the impact's origin along its path
};

/// A surface that takes impacts.
class ImpactReceiver {
public:
    virtual ~ImpactReceiver() = default;
    virtual const char* name() const = 0;
    /// Where `ray` first meets the surface as it is drawn now, or nothing.
    virtual std::optional<ImpactHit> hit(const Ray& ray) = 0;
    /// What the impact does at the hit.
    virtual void receive(const Impact& impact, const ImpactHit& hit) = 0;
};

struct RoutedImpact {
    size_t receiver; ///< index into the receivers given
    ImpactHit hit;
};

/// The one call: the impact goes to the receiver its path meets first. Nothing when it meets
/// none. Throws hfx::Error (and nothing receives it) on a bad impact.
std::optional<RoutedImpact> routeImpact(const Impact& impact, std::span<ImpactReceiver* const> receivers);

/// A decal wall drawn on a plane or on any mesh: a bullet hole or an explosion at the picked
/// texel, logged.
class WallImpacts final : public ImpactReceiver {
public:
    /// uvBounds: the patch's texcoords (hits outside are misses).
    WallImpacts(DecalWallEffect& wall, const SurfaceFrame& frame, glm::dvec4 uvBounds = {-1e30, -1e30, 1e30, 1e30});
    /// Drawn on `mesh` (kept: a copy, with its MeshPicker's hierarchy) with `model` and the
    /// wall's material as it is at each hit (pickMesh's pick: curved, faded at its silhouette,
    /// triplanar mapped). Throws hfx::Error naming a bad mesh (MeshData::validate) or a model
    /// matrix not finite or without an inverse.
    WallImpacts(DecalWallEffect& wall, MeshData mesh, const glm::mat4& model);
    const char* name() const override { return "wall"; }
    std::optional<ImpactHit> hit(const Ray& ray) override;
    void receive(const Impact& impact, const ImpactHit& hit) override;

private:
    DecalWallEffect& wall_;
    SurfaceFrame frame_{};
    glm::dvec4 bounds_{0.0};
    std::optional<MeshPicker> picker_; ///< drawn on a mesh, not on frame_
    glm::mat4 model_{1.0f};
};

/// The ocean drawn on a plane whose texcoords count its largest patch: a ring of waves there.
class OceanImpacts final : public ImpactReceiver {
public:
    OceanImpacts(OceanEffect& ocean, const SurfaceFrame& frame);
    const char* name() const override { return "ocean"; }
    /// Marches the ray through the relief's slab against OceanQuery's heights of the sea now
    /// (all cascades), then bisects to a millimetre.
    std::optional<ImpactHit> hit(const Ray& ray) override;
    void receive(const Impact& impact, const ImpactHit& hit) override;

private:
    OceanEffect& ocean_;
    SurfaceFrame frame_;
    std::unique_ptr<OceanQuery> query_;
};

/// The gas giant drawn on `sphere` (makeSphere's by default; pass the one you draw) with
/// `placement` times its own spin (GasPlanetEffect::modelMatrix()): a storm at the point the path
/// meets, picked on the relief as drawn (a MeshPicker of the sphere with the planet's material
/// and its surface's heights). Throws hfx::Error naming a bad mesh or placement.
class PlanetImpacts final : public ImpactReceiver {
public:
    PlanetImpacts(GasPlanetEffect& planet, MeshData sphere = makeSphere({}), const glm::mat4& placement = glm::mat4(1.0f));
    const char* name() const override { return "planet"; }
    std::optional<ImpactHit> hit(const Ray& ray) override;
    void receive(const Impact& impact, const ImpactHit& hit) override;

private:
    GasPlanetEffect& planet_;
    MeshPicker picker_;
    glm::mat4 placement_;
};

} // namespace hfx
