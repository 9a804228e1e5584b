#include "hfx/effects/Picking.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"
#include "hfx/effects/SurfaceRenderer.h"

#include "ModelMatrix.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
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

// What a mesh pick needs of the model, the ray and the material, checked once.
struct MeshPickSetup {
    glm::dmat4 m;
    glm::dmat3 m3, normalMatrix;
    double winding; ///< -1 under a mirroring model, which turns the front faces
    glm::dvec3 dir; ///< the ray's unit direction
};

void checkRay(const Ray& ray, const char* caller, const char* which) {
    if (!isFinite(ray.origin) || !isFinite(ray.direction) || !(glm::length(ray.direction) > 0.0))
        throw Error(str(caller, ": ", which, " must be finite and have a direction, got origin ", text(ray.origin),
                        " and direction ", text(ray.direction)));
}

MeshPickSetup checkedSetup(const Ray& ray, const glm::mat4& model, const SurfaceMaterial& material,
                           const std::optional<PixelNeighbours>& neighbours, const char* caller) {
    checkRay(ray, caller, "the ray");
    if (neighbours) {
        checkRay(neighbours->across, caller, "the neighbours' ray across");
        checkRay(neighbours->up, caller, "the neighbours' ray up");
    }
    checkModel(model, str(caller, ": ").c_str());
    {
        // The fields the pick reads; a shading model's look is not among them (and a water
        // look's environment check is a GL call, where this runs on any thread).
        SurfaceMaterial picked = material;
        picked.shading = Shading::Lit;
        picked.validate();
    }
    MeshPickSetup setup;
    setup.m = glm::dmat4(model);
    setup.m3 = glm::dmat3(setup.m);
    setup.normalMatrix = glm::transpose(glm::inverse(setup.m3));
    // Counter-clockwise seen from the normal side; a mirroring model turns the winding, and
    // the renderer its front faces with it.
    setup.winding = glm::determinant(setup.m3) < 0.0 ? -1.0 : 1.0;
    setup.dir = glm::normalize(ray.direction);
    return setup;
}

// A triangle the ray crosses, with its barycentric weights at the crossing and whether it faces
// the ray.
struct Crossing {
    double t;
    std::uint32_t triangle;
    glm::dvec3 weights;
    bool front;
};

// Where a ray from `origin` along the unit `dir` crosses the plane of triangle `k` (Moller-
// Trumbore in world space): its barycentric weights there and t along the ray; nothing where the
// ray runs in its plane or the triangle has no area, or under `inside` where it crosses the plane
// outside the triangle or not ahead of its origin.
std::optional<Crossing> crossPlane(const MeshPickSetup& setup, glm::dvec3 origin, glm::dvec3 dir, const MeshData& mesh,
                                   std::uint32_t k, bool inside) {
    const auto& v = mesh.vertices;
    const glm::dvec3 p0(setup.m * glm::dvec4(glm::dvec3(v[mesh.indices[3 * k]].position), 1.0));
    const glm::dvec3 p1(setup.m * glm::dvec4(glm::dvec3(v[mesh.indices[3 * k + 1]].position), 1.0));
    const glm::dvec3 p2(setup.m * glm::dvec4(glm::dvec3(v[mesh.indices[3 * k + 2]].position), 1.0));
    const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, q = glm::cross(dir, e2);
    const double det = glm::dot(e1, q);
    if (!(std::abs(det) > 1e-300)) return std::nullopt;
    const glm::dvec3 s = origin - p0, r = glm::cross(s, e1);
    const double b1 = glm::dot(s, q) / det, b2 = glm::dot(dir, r) / det, t = glm::dot(e2, r) / det;
    if (inside && (b1 < 0.0 || b2 < 0.0 || b1 + b2 > 1.0 || !(t > 0.0))) return std::nullopt;
    const bool front = setup.winding * glm::dot(glm::cross(e1, e2), dir) < 0.0;
    return Crossing{t, k, {1.0 - b1 - b2, b1, b2}, front};
}

// Where the ray crosses triangle `k`, if it does.
std::optional<Crossing> cross(const MeshPickSetup& setup, const Ray& ray, const MeshData& mesh, std::uint32_t k) {
    return crossPlane(setup, ray.origin, setup.dir, mesh, k, true);
}

// The pick along the crossings, as the draw's depth test decides it: each front face the ray
// crosses traces its own relief (or shows its polygon's point), and the nearest of those points
// shows. Its relief lies at or beyond where the ray crossed it, so the crossings are taken nearest
// first (ties in the triangles' order, so that any way of finding them gives the same pick) until
// one lies beyond the nearest point so far. A back face nearer than that shows itself (the mesh
// seen from behind or inside: nothing picked), unless the mesh is closed and a front face came
// first: there the renderer culls it, or it lies behind that face's polygon.
std::optional<MeshPick> pickAlong(std::vector<Crossing>& crossings, const MeshPickSetup& setup, const Ray& ray,
                                  const MeshData& mesh, const HeightFieldTracer& heights,
                                  const SurfaceMaterial& material, const std::optional<PixelNeighbours>& neighbours) {
    std::sort(crossings.begin(), crossings.end(),
              [](const Crossing& a, const Crossing& b) { return a.t < b.t || (a.t == b.t && a.triangle < b.triangle); });
    const auto& v = mesh.vertices;
    const glm::dvec3 dir = setup.dir;
    std::optional<MeshPick> nearest;
    double nearestT = std::numeric_limits<double>::infinity();
    bool frontCrossed = false;
    for (const Crossing& c : crossings) {
        if (c.t > nearestT) break;
        if (!c.front) {
            if (mesh.closed && frontCrossed) continue;
            return std::nullopt;
        }
        frontCrossed = true;
        // The vertex stage's outputs at the crossing (perspective-correct interpolation is the
        // barycentric weights of the point in space).
        glm::dvec3 objectPos(0.0), objectNormal(0.0), normal(0.0), tangent(0.0), bitangent(0.0);
        glm::dvec2 uv0(0.0);
        for (int i = 0; i < 3; ++i) {
            const Vertex& x = v[mesh.indices[3 * c.triangle + i]];
            const double w = c.weights[i];
            objectPos += w * glm::dvec3(x.position);
            objectNormal += w * glm::dvec3(x.normal);
            normal += w * (setup.normalMatrix * glm::dvec3(x.normal));
            tangent += w * (setup.m3 * glm::dvec3(x.tangent));
            bitangent += w * (setup.m3 * glm::dvec3(x.bitangent));
            uv0 += w * glm::dvec2(x.texcoord);
        }
        const glm::dvec3 entry = ray.origin + c.t * dir;
        int projection = -1;
        glm::dvec3 projectionNormal(0.0);
        if (material.triplanar.on()) {
            projectionNormal =
                glm::length(objectNormal) > 1e-6 ? glm::normalize(objectNormal) : glm::dvec3(0.0, 1.0, 0.0);
            projection = heaviestProjection(projectionNormal, material.triplanar.sharpness);
            const Projected f = projected(projection, projectionNormal, objectPos, material.triplanar.scale);
            uv0 = f.uv;
            tangent = setup.m3 * f.tangent;
            bitangent = setup.m3 * f.bitangent;
        }
        // The draw's level of detail (surface.frag): the mip level of the texcoords' spread to
        // the neighbouring pixels, whose rays cross the triangle's plane where their texcoords are
        // interpolated (or projected); `flatten`, how far the point shown slides back from the
        // hit to the polygon (1: normal mapped).
        double flatten = 0.0;
        if (neighbours) {
            const glm::dvec2 texels(heights.width(), heights.height());
            double spread = 0.0; // the longer, squared, in texels
            for (const Ray* r : {&neighbours->across, &neighbours->up}) {
                const auto w = crossPlane(setup, r->origin, glm::normalize(r->direction), mesh, c.triangle, false);
                if (!w || !(w->t > 0.0)) { // the neighbour's ray misses the plane: the spread is endless
                    spread = std::numeric_limits<double>::infinity();
                    break;
                }
                glm::dvec2 uv(0.0);
                if (projection >= 0) {
                    glm::dvec3 p(0.0);
                    for (int i = 0; i < 3; ++i)
                        p += w->weights[i] * glm::dvec3(v[mesh.indices[3 * c.triangle + i]].position);
                    uv = projected(projection, projectionNormal, p, material.triplanar.scale).uv;
                } else {
                    for (int i = 0; i < 3; ++i)
                        uv += w->weights[i] * glm::dvec2(v[mesh.indices[3 * c.triangle + i]].texcoord);
                }
                const glm::dvec2 d = (uv - uv0) * texels;
                spread = std::max(spread, glm::dot(d, d));
            }
            const double level = 0.5 * std::log2(std::max(spread, 1e-12)), threshold = material.lodThreshold;
            flatten = std::clamp(level - (threshold - 1.0), 0.0, 1.0);
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
        std::optional<SurfacePick> hit;
        if (!frameOk || !(depthScale > 0.0) || !(glm::dot(unitNormal, -dir) > 0.0) || flatten >= 1.0) {
            // No texture space, no relief, the view at or past the entry normal's horizon, or
            // past the level of detail: normal mapped, the polygon's point at its texcoords.
            hit = SurfacePick{uv0, entry, heights.heightAt(uv0)};
        } else {
            const SurfaceFrame frame{entry - tangent * uv0.x - bitangent * uv0.y, tangent, bitangent, unitNormal};
            hit = pickSurface(ray, frame, heights, depthScale);
            if (hit && flatten > 0.0) {
                hit->uv = glm::mix(hit->uv, uv0, flatten);
                hit->world = glm::mix(hit->world, entry, flatten);
                hit->height = heights.heightAt(hit->uv);
            }
        }
        // (None, or a point off the patch: its pixel discarded; the next triangle shows.)
        if (material.clipToPatch && hit) {
            const glm::dvec4 bounds(material.patchBounds);
            if (hit->uv.x < bounds.x || hit->uv.y < bounds.y || hit->uv.x > bounds.z || hit->uv.y > bounds.w)
                hit.reset();
        }
        if (!hit) continue;
        const double t = glm::dot(hit->world - ray.origin, dir);
        if (t < nearestT) {
            nearest = MeshPick{*hit, c.triangle, entry, unitNormal, projection};
            nearestT = t;
        }
    }
    return nearest;
}

} // namespace

PixelNeighbours PixelNeighbours::of(const Camera& camera, double x, double y, int width, int height) {
    // The other pixel of its 2x2 quad across and up: quads start at even window coordinates.
    const double across = (static_cast<long long>(std::floor(x)) & 1) != 0 ? -1.0 : 1.0;
    const double up = (static_cast<long long>(std::floor(y)) & 1) != 0 ? -1.0 : 1.0;
    return {camera.rayThroughPixel(x + across, y, width, height), camera.rayThroughPixel(x, y + up, width, height)};
}

std::optional<MeshPick> pickMesh(const Ray& ray, const MeshData& mesh, const glm::mat4& model,
                                 const HeightFieldTracer& heights, const SurfaceMaterial& material,
                                 const std::optional<PixelNeighbours>& neighbours) {
    const MeshPickSetup setup = checkedSetup(ray, model, material, neighbours, "pickMesh");
    mesh.validate();
    // Every triangle the ray crosses.
    std::vector<Crossing> crossings;
    for (std::uint32_t k = 0; 3 * size_t(k) + 2 < mesh.indices.size(); ++k)
        if (const auto c = cross(setup, ray, mesh, k)) crossings.push_back(*c);
    return pickAlong(crossings, setup, ray, mesh, heights, material, neighbours);
}

MeshPicker::MeshPicker(MeshData mesh) : mesh_((mesh.validate(), std::move(mesh))) {
    // A bounding volume hierarchy over the triangles in object space: each node's box holds its
    // triangles; a node of more than 4 splits at the median of their centroids along the longest
    // axis of the centroids' box (O(n log n)).
    const size_t triangles = mesh_.indices.size() / 3;
    order_.resize(triangles);
    std::vector<glm::dvec3> lo(triangles), hi(triangles), centre(triangles);
    for (size_t k = 0; k < triangles; ++k) {
        order_[k] = std::uint32_t(k);
        const glm::dvec3 a(mesh_.vertices[mesh_.indices[3 * k]].position),
            b(mesh_.vertices[mesh_.indices[3 * k + 1]].position), c(mesh_.vertices[mesh_.indices[3 * k + 2]].position);
        lo[k] = glm::min(a, glm::min(b, c));
        hi[k] = glm::max(a, glm::max(b, c));
        centre[k] = (a + b + c) / 3.0;
    }
    // Boxes grow by a millionth of the mesh's size: a triangle the world-space crossing accepts
    // on its edge is never pruned by the object-space box test's rounding.
    glm::dvec3 meshLo(1e300), meshHi(-1e300);
    for (size_t k = 0; k < triangles; ++k) meshLo = glm::min(meshLo, lo[k]), meshHi = glm::max(meshHi, hi[k]);
    const double pad = 1e-6 * std::max(glm::length(meshHi - meshLo), 1e-30);
    struct Range {
        std::uint32_t node, first, count;
    };
    nodes_.push_back({});
    std::vector<Range> pending{{0, 0, std::uint32_t(triangles)}};
    while (!pending.empty()) {
        const Range r = pending.back();
        pending.pop_back();
        glm::dvec3 boxLo(1e300), boxHi(-1e300), cLo(1e300), cHi(-1e300);
        for (std::uint32_t i = r.first; i < r.first + r.count; ++i) {
            const std::uint32_t k = order_[i];
            boxLo = glm::min(boxLo, lo[k]), boxHi = glm::max(boxHi, hi[k]);
            cLo = glm::min(cLo, centre[k]), cHi = glm::max(cHi, centre[k]);
        }
        Node& node = nodes_[r.node];
        node.lo = boxLo - pad;
        node.hi = boxHi + pad;
        const glm::dvec3 extent = cHi - cLo;
        if (r.count <= 4 || !(std::max({extent.x, extent.y, extent.z}) > 0.0)) {
            node.first = r.first;
            node.count = r.count;
            continue;
        }
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const std::uint32_t half = r.count / 2;
        std::nth_element(order_.begin() + r.first, order_.begin() + r.first + half, order_.begin() + r.first + r.count,
                         [&](std::uint32_t a, std::uint32_t b) { return centre[a][axis] < centre[b][axis]; });
        const std::uint32_t left = std::uint32_t(nodes_.size());
        nodes_[r.node].first = left; // an inner node: its children are left and left + 1
        nodes_[r.node].count = 0;
        nodes_.push_back({});
        nodes_.push_back({});
        pending.push_back({left, r.first, half});
        pending.push_back({left + 1, r.first + half, r.count - half});
    }
}

std::optional<MeshPick> MeshPicker::pick(const Ray& ray, const glm::mat4& model, const HeightFieldTracer& heights,
                                         const SurfaceMaterial& material,
                                         const std::optional<PixelNeighbours>& neighbours) const {
    const MeshPickSetup setup = checkedSetup(ray, model, material, neighbours, "MeshPicker::pick");
    // The ray in object space (the model is affine: a point at t along it is the world ray's at t).
    const glm::dmat4 inverse = glm::inverse(setup.m);
    const glm::dvec3 o(inverse * glm::dvec4(ray.origin, 1.0)), d(inverse * glm::dvec4(setup.dir, 0.0));
    const glm::dvec3 invD(1.0 / d.x, 1.0 / d.y, 1.0 / d.z);
    auto enters = [&](const Node& n) {
        // The slabs' test; an axis the ray runs along (d 0, invD infinite) holds the ray wholly
        // or not at all, by where its origin lies.
        double t0 = 0.0, t1 = 1e300;
        for (int a = 0; a < 3; ++a) {
            if (d[a] == 0.0) {
                if (o[a] < n.lo[a] || o[a] > n.hi[a]) return false;
                continue;
            }
            const double ta = (n.lo[a] - o[a]) * invD[a], tb = (n.hi[a] - o[a]) * invD[a];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
        }
        return t0 <= t1;
    };
    std::vector<Crossing> crossings;
    std::vector<std::uint32_t> stack{0};
    stack.reserve(64);
    while (!stack.empty()) {
        const Node& n = nodes_[stack.back()];
        stack.pop_back();
        if (!enters(n)) continue;
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
                if (const auto c = cross(setup, ray, mesh_, order_[i])) crossings.push_back(*c);
        } else {
            stack.push_back(n.first);
            stack.push_back(n.first + 1);
        }
    }
    return pickAlong(crossings, setup, ray, mesh_, heights, material, neighbours);
}

} // namespace hfx
