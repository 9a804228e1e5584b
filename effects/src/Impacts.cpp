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
#include <numbers>
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
    : wall_(wall), mesh_(std::move(mesh)), model_(model) {
    mesh_->validate();
    checkModel(model, "WallImpacts: ");
}

std::optional<ImpactHit> WallImpacts::hit(const Ray& ray) {
    if (mesh_) {
        const auto pick = wall_.pick(ray, *mesh_, model_, wall_.material());
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

PlanetImpacts::PlanetImpacts(GasPlanetEffect& planet, glm::dvec3 centre, double radius)
    : planet_(planet), centre_(centre), radius_(radius) {
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw Error(str("PlanetImpacts: radius must be positive and finite, got ", radius));
}

std::optional<ImpactHit> PlanetImpacts::hit(const Ray& ray) {
    // Into the planet's own frame (makeSphere's, radius 1).
    const glm::dmat3 spin(glm::dmat4(planet_.modelMatrix()));
    const glm::dmat3 unspin = glm::transpose(spin);
    const glm::dvec3 o = unspin * ((ray.origin - centre_) / radius_), d = unspin * ray.direction; // |d| = 1
    const double b = glm::dot(o, d), c = glm::dot(o, o) - 1.0, disc = b * b - c;
    if (disc < 0.0) return std::nullopt;
    const double enter = -b - std::sqrt(disc), leave = -b + std::sqrt(disc);
    if (leave < 0.0) return std::nullopt;
    const double pi = std::numbers::pi;
    auto uvOf = [&](const glm::dvec3& p) {
        const glm::dvec3 n = glm::normalize(p);
        const double lat = std::asin(std::clamp(n.y, -1.0, 1.0)), lon = std::atan2(-n.z, n.x);
        return glm::dvec2(wrap01(lon / (2.0 * pi)), std::clamp(lat / pi + 0.5, 0.0, 1.0));
    };
    const GasConfig& gas = planet_.gas().config();
    const std::vector<float> heights = planet_.readHeights();
    auto height = [&](glm::dvec2 uv) { // bilinear, texel centres at (i + 0.5) / W, u wraps
        const int W = gas.width, H = gas.height;
        const double x = uv.x * W - 0.5, y = std::clamp(uv.y * H - 0.5, 0.0, double(H - 1));
        const int i = int(std::floor(x)), j = std::min(int(std::floor(y)), H - 2);
        const double ax = x - i, ay = y - j;
        auto at = [&](int a, int bRow) { return double(heights[size_t(bRow) * W + size_t(((a % W) + W) % W)]); };
        return (1 - ay) * ((1 - ax) * at(i, j) + ax * at(i + 1, j)) + ay * ((1 - ax) * at(i, j + 1) + ax * at(i + 1, j + 1));
    };
    // The relief's depth (radii) where the path enters, as the shader scales it: depthScale
    // texture units of sqrt(|dP/du| |dP/dv|) = sqrt(2 pi cos(lat) pi), faded at the silhouette.
    const SurfaceMaterial& m = planet_.material();
    const glm::dvec3 p0 = o + std::max(enter, 0.0) * d;
    const double cosLat = std::sqrt(std::max(0.0, 1.0 - glm::normalize(p0).y * glm::normalize(p0).y));
    const double cosView = std::clamp(-glm::dot(glm::normalize(p0), d), 0.0, 1.0);
    const double fade = m.silhouetteFade > 0.0f
                            ? [&] { const double t = std::clamp(cosView / m.silhouetteFade, 0.0, 1.0); return t * t * (3 - 2 * t); }()
                            : 1.0;
    const double depth = double(m.depthScale) * std::sqrt(2.0 * pi * cosLat * pi) * fade;
    // March from the shell to where the path leaves the relief, then bisect: the first point whose
    // radius is at or below the surface's, 1 - (1 - h) depth.
    auto below = [&](double t) {
        const glm::dvec3 p = o + t * d;
        return glm::length(p) <= 1.0 - (1.0 - height(uvOf(p))) * depth;
    };
    const double start = std::max(enter, 0.0);
    const double b2 = glm::dot(o, d), c2 = glm::dot(o, o) - (1.0 - depth) * (1.0 - depth), disc2 = b2 * b2 - c2;
    const double end = disc2 >= 0.0 ? -b2 - std::sqrt(disc2) : leave; // the inner sphere, or out again
    constexpr int steps = 512;
    double found = -1.0;
    for (int i = 0; i <= steps; ++i) {
        const double t = start + (end - start) * i / steps;
        if (!below(t)) continue;
        double lo = i > 0 ? start + (end - start) * (i - 1) / steps : start, hi = t;
        for (int k = 0; k < 40; ++k) (below(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
        found = hi;
        break;
    }
    if (found < 0.0) found = std::max(end, start); // a grazing path: its deepest point
    const glm::dvec3 p = o + found * d;
    const glm::dvec3 world = centre_ + radius_ * (spin * p);
    return ImpactHit{world, uvOf(p), glm::normalize(spin * p), found * radius_};
}

void PlanetImpacts::receive(const Impact& impact, const ImpactHit& hit) {
    // A blast stirs a storm four times a bullet's energy; the seed picks the spin.
    const float strength = impact.energy * (impact.kind == ImpactKind::Explosion ? 4.0f : 1.0f);
    planet_.addStorm(float(hit.uv.x), float(hit.uv.y), (impact.seed & 1u) != 0, strength);
}

} // namespace hfx
