#include "hfx/effects/Picking.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"
#include "hfx/effects/SurfaceRenderer.h"

#include "ModelMatrix.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace hfx {

SurfaceFrame SurfaceFrame::ofPlane(const PlaneConfig& plane, const glm::mat4& model) {
    plane.validate();
    // makePlane: position = ((s - 0.5) size, 0, (0.5 - t) size) for texcoords (s, t) * scale.
    const double perTexcoord = double(plane.size) / plane.texcoordScale;
    const glm::dmat4 m(model);
    const glm::dvec3 origin = glm::dvec3(m * glm::dvec4(-0.5 * plane.size, 0.0, 0.5 * plane.size, 1.0));
    const glm::dvec3 tangent = glm::dvec3(m * glm::dvec4(perTexcoord, 0.0, 0.0, 0.0));
    const glm::dvec3 bitangent = glm::dvec3(m * glm::dvec4(0.0, 0.0, -perTexcoord, 0.0));
    // The plane's normal (+Y) turned as the renderer turns it (the normal matrix): a mirroring
    // model keeps the relief on that side, where T x B would turn to the other.
    const glm::dvec3 normal = glm::transpose(glm::inverse(glm::dmat3(m))) * glm::dvec3(0.0, 1.0, 0.0);
    return {origin, tangent, bitangent, glm::normalize(normal)};
}

std::optional<SurfacePick> pickSurface(const Ray& ray, const SurfaceFrame& frame,
                                       const HeightFieldTracer& heights, double depthScale,
                                       glm::dvec4 uvBounds) {
    if (!(depthScale >= 0.0) || !std::isfinite(depthScale))
        throw Error(str("pickSurface: depthScale must be >= 0 and finite, got ", depthScale));
    if (!isFinite(ray.origin) || !isFinite(ray.direction) || !(glm::length(ray.direction) > 0.0))
        throw Error(str("pickSurface: the ray must be finite and have a direction, got origin ", text(ray.origin),
                        " and direction ", text(ray.direction)));
    if (!isFinite(frame.origin) || !isFinite(frame.tangent) || !isFinite(frame.bitangent) || !isFinite(frame.normal))
        throw Error(str("pickSurface: the surface frame must be finite, got origin ", text(frame.origin), ", tangent ",
                        text(frame.tangent), ", bitangent ", text(frame.bitangent), ", normal ", text(frame.normal)));
    // Texture space as the shader builds it: columns T, B and the normal scaled to one
    // texcoord's length; its z is the depth below the patch in texture units.
    const double unitsPerTexcoord = std::sqrt(glm::length(frame.tangent) * glm::length(frame.bitangent));
    const glm::dmat3 worldFromTexture(frame.tangent, frame.bitangent, frame.normal * unitsPerTexcoord);
    if (std::abs(glm::determinant(worldFromTexture)) < 1e-300) return std::nullopt;
    const glm::dmat3 textureFromWorld = glm::inverse(worldFromTexture);
    const glm::dvec3 o = textureFromWorld * (ray.origin - frame.origin);
    const glm::dvec3 d = textureFromWorld * ray.direction;
    // (u, v, h) with h = 1 + z / depthScale; a flat surface (depthScale 0) is the patch itself.
    auto toWorld = [&](glm::dvec2 uv, double h) {
        return frame.origin + worldFromTexture * glm::dvec3(uv, (h - 1.0) * depthScale);
    };
    auto inBounds = [&](glm::dvec2 uv) {
        return uv.x >= uvBounds.x && uv.y >= uvBounds.y && uv.x <= uvBounds.z && uv.y <= uvBounds.w;
    };
    if (depthScale == 0.0) {
        if (!(d.z < 0.0) || o.z < 0.0) return std::nullopt;
        const glm::dvec2 uv = glm::dvec2(o) + glm::dvec2(d) * (-o.z / d.z);
        if (!inBounds(uv)) return std::nullopt;
        return SurfacePick{uv, toWorld(uv, 1.0), heights.heightAt(uv)};
    }
    glm::dvec3 origin(o.x, o.y, 1.0 + o.z / depthScale);
    const glm::dvec3 direction(d.x, d.y, d.z / depthScale);
    // Start where the ray enters the slab h <= 1 and stop where it leaves through h = 0.
    if (origin.z > 1.0) {
        if (!(direction.z < 0.0)) return std::nullopt;
        origin += direction * ((1.0 - origin.z) / direction.z);
        origin.z = 1.0;
    }
    if (origin.z < 0.0) return std::nullopt;
    double tMax;
    if (direction.z < 0.0) tMax = -origin.z / direction.z;
    else return std::nullopt; // looking up from inside the relief: nothing sensible to pick
    const auto hit = heights.intersect(origin, direction, tMax * (1.0 + 1e-9));
    if (!hit || !inBounds(hit->uv)) return std::nullopt;
    return SurfacePick{hit->uv, toWorld(hit->uv, hit->height), hit->height};
}

namespace {

/// The triplanar mapping's frame of projection `axis` at a point of the mesh whose own position
/// is `p` and unit normal `n` (surface.frag's hfx_projected_frame): the texcoords and dP/du,
/// dP/dv in the mesh's space.
struct Projected {
    glm::dvec2 uv;
    glm::dvec3 tangent, bitangent;
};
Projected projected(int axis, glm::dvec3 n, glm::dvec3 p, double scale) {
    const double side = n[axis] < 0.0 ? -1.0 : 1.0;
    glm::dvec3 ea(0.0);
    ea[axis] = 1.0;
    const glm::dvec3 eu = axis == 0 ? glm::dvec3(0.0, side, 0.0) : glm::dvec3(side, 0.0, 0.0);
    const glm::dvec3 ev = axis == 0 ? glm::dvec3(0.0, 0.0, 1.0) : axis == 1 ? glm::dvec3(0.0, 0.0, -1.0) : glm::dvec3(0.0, 1.0, 0.0);
    return {scale * glm::dvec2(glm::dot(eu, p), glm::dot(ev, p)), (eu - glm::dot(n, eu) / n[axis] * ea) / scale,
            (ev - glm::dot(n, ev) / n[axis] * ea) / scale};
}

/// The heaviest of the triplanar weights of the unit normal `n` (surface.frag's main: |n| less
/// the dead zone, to the power `sharpness`; the first of equals).
int heaviestProjection(glm::dvec3 n, double sharpness) {
    constexpr double kDeadZone = 0.3; // HFX_TRIPLANAR_DEAD_ZONE
    glm::dvec3 w;
    for (int k = 0; k < 3; ++k) w[k] = std::pow(std::max(std::abs(n[k]) - kDeadZone, 0.0), sharpness);
    return w.x >= w.y && w.x >= w.z ? 0 : w.y >= w.z ? 1 : 2;
}

} // namespace

std::optional<MeshPick> pickMesh(const Ray& ray, const MeshData& mesh, const glm::mat4& model,
                                 const HeightFieldTracer& heights, const SurfaceMaterial& material) {
    if (!isFinite(ray.origin) || !isFinite(ray.direction) || !(glm::length(ray.direction) > 0.0))
        throw Error(str("pickMesh: the ray must be finite and have a direction, got origin ", text(ray.origin),
                        " and direction ", text(ray.direction)));
    checkModel(model, "pickMesh: ");
    const glm::dmat4 m(model);
    const glm::dmat3 m3(m);
    mesh.validate();
    {
        // The fields the pick reads; a shading model's look is not among them (and a water
        // look's environment check is a GL call, where this runs on any thread).
        SurfaceMaterial picked = material;
        picked.shading = Shading::Lit;
        picked.validate();
    }
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(m3));
    // Counter-clockwise seen from the normal side; a mirroring model turns the winding, and
    // the renderer its front faces with it.
    const double winding = glm::determinant(m3) < 0.0 ? -1.0 : 1.0;
    const glm::dvec3 dir = glm::normalize(ray.direction);

    // Every triangle the ray crosses, nearest first (Moller-Trumbore in world space), with its
    // barycentric weights at the crossing and whether it faces the ray.
    struct Crossing {
        double t;
        std::uint32_t triangle;
        glm::dvec3 weights;
        bool front;
    };
    std::vector<Crossing> crossings;
    const auto& v = mesh.vertices;
    for (size_t k = 0; k + 2 < mesh.indices.size(); k += 3) {
        const glm::dvec3 p0(m * glm::dvec4(glm::dvec3(v[mesh.indices[k]].position), 1.0));
        const glm::dvec3 p1(m * glm::dvec4(glm::dvec3(v[mesh.indices[k + 1]].position), 1.0));
        const glm::dvec3 p2(m * glm::dvec4(glm::dvec3(v[mesh.indices[k + 2]].position), 1.0));
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, q = glm::cross(dir, e2);
        const double det = glm::dot(e1, q);
        if (!(std::abs(det) > 1e-300)) continue; // the ray runs in its plane, or it has no area
        const glm::dvec3 s = ray.origin - p0, r = glm::cross(s, e1);
        const double b1 = glm::dot(s, q) / det, b2 = glm::dot(dir, r) / det, t = glm::dot(e2, r) / det;
        if (b1 < 0.0 || b2 < 0.0 || b1 + b2 > 1.0 || !(t > 0.0)) continue;
        const bool front = winding * glm::dot(glm::cross(e1, e2), dir) < 0.0;
        crossings.push_back({t, std::uint32_t(k / 3), {1.0 - b1 - b2, b1, b2}, front});
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) { return a.t < b.t; });

    for (const Crossing& c : crossings) {
        if (!c.front) return std::nullopt; // seen from behind: the back face is what shows
        // The vertex stage's outputs at the crossing (perspective-correct interpolation is the
        // barycentric weights of the point in space).
        glm::dvec3 objectPos(0.0), objectNormal(0.0), normal(0.0), tangent(0.0), bitangent(0.0);
        glm::dvec2 uv0(0.0);
        for (int i = 0; i < 3; ++i) {
            const Vertex& x = v[mesh.indices[3 * c.triangle + i]];
            const double w = c.weights[i];
            objectPos += w * glm::dvec3(x.position);
            objectNormal += w * glm::dvec3(x.normal);
            normal += w * (normalMatrix * glm::dvec3(x.normal));
            tangent += w * (m3 * glm::dvec3(x.tangent));
            bitangent += w * (m3 * glm::dvec3(x.bitangent));
            uv0 += w * glm::dvec2(x.texcoord);
        }
        const glm::dvec3 entry = ray.origin + c.t * dir;
        int projection = -1;
        if (material.triplanar.on()) {
            const glm::dvec3 n = glm::length(objectNormal) > 1e-6 ? glm::normalize(objectNormal) : glm::dvec3(0.0, 1.0, 0.0);
            projection = heaviestProjection(n, material.triplanar.sharpness);
            const Projected f = projected(projection, n, objectPos, material.triplanar.scale);
            uv0 = f.uv;
            tangent = m3 * f.tangent;
            bitangent = m3 * f.bitangent;
        }
        // hfx_surface: a degenerate frame is normal mapped; the relief fades out as the view
        // grazes the entry's normal.
        const glm::dvec3 unitNormal = glm::length(normal) > 0.0 ? glm::normalize(normal) : glm::dvec3(0.0);
        const bool frameOk = glm::length(tangent) > 1e-3 * glm::length(bitangent) &&
                             glm::length(bitangent) > 1e-3 * glm::length(tangent);
        double depthScale = frameOk ? double(material.depthScale) : 0.0;
        if (frameOk && material.silhouetteFade > 0.0f) {
            const double cosView = std::clamp(glm::dot(unitNormal, -dir), 0.0, 1.0);
            const double x = std::clamp(cosView / double(material.silhouetteFade), 0.0, 1.0);
            depthScale *= x * x * (3.0 - 2.0 * x);
        }
        glm::dvec4 bounds(-1e30, -1e30, 1e30, 1e30);
        if (material.clipToPatch) bounds = glm::dvec4(material.patchBounds);
        std::optional<SurfacePick> hit;
        if (!frameOk || !(depthScale > 0.0) || !(glm::dot(unitNormal, -dir) > 0.0)) {
            // No texture space, no relief, or the view at or past the entry normal's horizon:
            // normal mapped, the polygon's point at its texcoords.
            if (uv0.x >= bounds.x && uv0.y >= bounds.y && uv0.x <= bounds.z && uv0.y <= bounds.w)
                hit = SurfacePick{uv0, entry, heights.heightAt(uv0)};
        } else {
            const SurfaceFrame frame{entry - tangent * uv0.x - bitangent * uv0.y, tangent, bitangent, unitNormal};
            hit = pickSurface(ray, frame, heights, depthScale, bounds);
        }
        if (hit) return MeshPick{*hit, c.triangle, entry, unitNormal, projection};
        // Its pixel discarded (the ray left the patch): the next triangle along the ray shows.
    }
    return std::nullopt;
}

} // namespace hfx
