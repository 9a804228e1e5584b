#include "hfx/effects/Impacts.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"
#include "hfx/effects/DecalWallEffect.h"
#include "hfx/effects/GasPlanetEffect.h"
#include "hfx/effects/OceanEffect.h"

#include "ModelMatrix.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace hfx {

void Impact::validate() const {
    if (!isFinite(origin)) throw Error(str("Impact.origin must be finite, got ", text(origin)));
    const double length = glm::length(direction);
    if (!(length > 0.0) || !std::isfinite(length))
        throw Error(str("Impact.direction must be finite and not zero, got ", text(direction)));
    if (!(energy > 0.0f) || !std::isfinite(energy))
        throw Error(str("Impact.energy must be positive and finite, got ", energy));
    if (kind != ImpactKind::Bullet && kind != ImpactKind::Explosion)
        throw Error(str("Impact.kind ", int(kind), " is neither a bullet nor an explosion"));
}

std::optional<RoutedImpact> routeImpact(const Impact& impact, std::span<ImpactReceiver* const> receivers) {
    impact.validate();
    const Ray ray{impact.origin, glm::normalize(impact.direction)};
    std::optional<RoutedImpact> first;
    for (size_t i = 0; i < receivers.size(); ++i)
        if (const auto hit = receivers[i]->hit(ray); hit && (!first || hit->distance < first->hit.distance))
            first = RoutedImpact{i, *hit};
    if (first) receivers[first->receiver]->receive(impact, first->hit);
    return first;
}

namespace {
double wrap01(double x) {
    const double w = x - std::floor(x);
    return w >= 1.0 ? 0.0 : w;
}
} // namespace

// --- the wall

WallImpacts::WallImpacts(DecalWallEffect& wall, const SurfaceFrame& frame, glm::dvec4 uvBounds)
    : wall_(wall), frame_(frame), bounds_(uvBounds) {}

WallImpacts::WallImpacts(DecalWallEffect& wall, MeshData mesh, const glm::mat4& model)
    : wall_(wall), picker_(std::move(mesh)), model_(model) {
    checkModel(model, "WallImpacts: ");
}

std::optional<ImpactHit> WallImpacts::hit(const Ray& ray) {
    if (picker_) {
        const auto pick = picker_->pick(ray, model_, wall_.heightTracer(), wall_.material());
        if (!pick) return std::nullopt;
        return ImpactHit{pick->world, pick->uv, pick->normal, glm::length(pick->world - ray.origin)};
    }
    const auto pick = pickSurface(ray, frame_, wall_.heightTracer(), wall_.material().depthScale, bounds_);
    if (!pick) return std::nullopt;
    return ImpactHit{pick->world, pick->uv, frame_.normal, glm::length(pick->world - ray.origin)};
}

void WallImpacts::receive(const Impact& impact, const ImpactHit& hit) {
    const DamageLook& look = wall_.config().damage.look;
    const float base = impact.kind == ImpactKind::Bullet ? look.bullet.radius : look.explosion.radius;
    wall_.impact({.u = float(wrap01(hit.uv.x)),
                  .v = float(wrap01(hit.uv.y)),
                  .nx = float(hit.normal.x),
                  .ny = float(hit.normal.y),
                  .nz = float(hit.normal.z),
                  .radius = std::min(base * std::cbrt(impact.energy), 1.0f),
                  .kind = impact.kind,
                  .seed = impact.seed});
}

// --- the ocean

OceanImpacts::OceanImpacts(OceanEffect& ocean, const SurfaceFrame& frame)
    : ocean_(ocean), frame_(frame), query_(std::make_unique<OceanQuery>(ocean.ocean())) {}

std::optional<ImpactHit> OceanImpacts::hit(const Ray& ray) {
    query_->update(ocean_.ocean()); // the spectra of now (a wind change may be blending)
    const OceanField& sea = ocean_.ocean();
    double sigmas = 0.0;
    for (int i = 0; i < sea.cascadeCount(); ++i) sigmas += sea.cascade(i).sigma;
    // The drawn surface: h = 0.5 + M / (8 sum sigma) over the mesh's texcoords (M the sea's
    // height in metres, the sum of the cascades), the polygon at h = 1 and h = 0 `depth` below.
    const double unitsPerTexcoord = std::sqrt(glm::length(frame_.tangent) * glm::length(frame_.bitangent));
    const double depth = double(ocean_.material().depthScale) * unitsPerTexcoord;
    const double patch = sea.config().patchMeters, scale = sigmas > 0.0 ? depth / (8.0 * sigmas) : 0.0;
    const glm::dmat3 basis(frame_.tangent, frame_.bitangent, frame_.normal);
    const glm::dmat3 toFrame = glm::inverse(basis);
    // Along the ray: texcoords and the offset above the polygon.
    auto local = [&](double t) { return toFrame * (ray.origin + t * ray.direction - frame_.origin); };
    const glm::dvec3 o = local(0.0), d = toFrame * ray.direction;
    if (std::abs(d.z) < 1e-12) return std::nullopt;
    // The slab between the polygon (offset 0) and depth below it, where the ray is inside.
    double t0 = (0.0 - o.z) / d.z, t1 = (-depth - o.z) / d.z;
    if (t0 > t1) std::swap(t0, t1);
    t0 = std::max(t0, 0.0);
    if (t1 <= t0) return std::nullopt;
    const double time = sea.time();
    auto gap = [&](std::span<const double> ts, std::vector<double>& out) { // ray offset - surface offset
        std::vector<glm::vec2> points;
        for (double t : ts) {
            const glm::dvec3 p = local(t);
            points.emplace_back(float(p.x * patch), float(p.y * patch));
        }
        const std::vector<float> metres = query_->heights(points, time);
        out.resize(ts.size());
        for (size_t i = 0; i < ts.size(); ++i) out[i] = local(ts[i]).z - (-0.5 * depth + scale * metres[i]);
    };
    constexpr int steps = 256;
    std::vector<double> ts(steps + 1), gaps;
    for (int i = 0; i <= steps; ++i) ts[size_t(i)] = t0 + (t1 - t0) * i / steps;
    gap(ts, gaps);
    for (int i = 0; i <= steps; ++i) {
        if (gaps[size_t(i)] > 0.0) continue;
        double lo = i > 0 ? ts[size_t(i - 1)] : t0, hi = ts[size_t(i)];
        std::vector<double> one(1), g;
        for (int k = 0; k < 40 && hi - lo > 1e-4; ++k) { // to a tenth of a millimetre of the path
            one[0] = 0.5 * (lo + hi);
            gap(one, g);
            (g[0] > 0.0 ? lo : hi) = one[0];
        }
        const double t = hi;
        const glm::dvec3 p = local(t);
        return ImpactHit{ray.origin + t * ray.direction, glm::dvec2(p.x, p.y), frame_.normal, t};
    }
    return std::nullopt;
}

void OceanImpacts::receive(const Impact& impact, const ImpactHit& hit) {
    ocean_.disturb(hit.uv, impact.energy, impact.kind);
}

// --- the planet

PlanetImpacts::PlanetImpacts(GasPlanetEffect& planet, MeshData sphere, const glm::mat4& placement)
    : planet_(planet), picker_(std::move(sphere)), placement_(placement) {
    checkModel(placement, "PlanetImpacts: ");
}

std::optional<ImpactHit> PlanetImpacts::hit(const Ray& ray) {
    // The surface's heights (the gas's, or its detail's, surfaceWidth() x surfaceHeight()), wrapping
    // at the date line and clamped at the poles.
    const HeightFieldTracer heights(planet_.readHeights(), planet_.surfaceWidth(), planet_.surfaceHeight(),
                                    EdgeMode::WrapU);
    const auto pick = picker_.pick(ray, placement_ * planet_.modelMatrix(), heights, planet_.material());
    if (!pick) return std::nullopt;
    // A storm's place on the gas: longitude wrapped into [0, 1), latitude within the poles.
    const glm::dvec2 uv(wrap01(pick->uv.x), std::clamp(pick->uv.y, 0.0, 1.0));
    return ImpactHit{pick->world, uv, pick->normal, glm::length(pick->world - ray.origin)};
}

void PlanetImpacts::receive(const Impact& impact, const ImpactHit& hit) {
    // A blast stirs a storm four times a bullet's energy; the seed picks the spin.
    const float strength = impact.energy * (impact.kind == ImpactKind::Explosion ? 4.0f : 1.0f);
    planet_.addStorm(float(hit.uv.x), float(hit.uv.y), (impact.seed & 1u) != 0, strength);
}

} // namespace hfx
