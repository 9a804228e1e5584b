#include "hfx/effects/Picking.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <cmath>

namespace hfx {

SurfaceFrame SurfaceFrame::ofPlane(const PlaneConfig& plane, const glm::mat4& model) {
    plane.validate();
    // makePlane: position = ((s - 0.5) size, 0, (0.5 - t) size) for texcoords (s, t) * scale.
    const double perTexcoord = double(plane.size) / plane.texcoordScale;
    const glm::dmat4 m(model);
    const glm::dvec3 origin = glm::dvec3(m * glm::dvec4(-0.5 * plane.size, 0.0, 0.5 * plane.size, 1.0));
    const glm::dvec3 tangent = glm::dvec3(m * glm::dvec4(perTexcoord, 0.0, 0.0, 0.0));
    const glm::dvec3 bitangent = glm::dvec3(m * glm::dvec4(0.0, 0.0, -perTexcoord, 0.0));
    return {origin, tangent, bitangent, glm::normalize(glm::cross(tangent, bitangent))};
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

} // namespace hfx
