#include "hfx/core/Camera.h"

#include "hfx/core/Error.h"
#include "hfx/core/Finite.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace hfx {

void Camera::validate() const {
    for (const auto& [name, value] : {std::pair("position", position), std::pair("target", target), std::pair("up", up)})
        if (!isFinite(value)) throw Error(str("Camera.", name, " must be finite, got ", text(value)));
    if (!isFinite(jitter)) throw Error(str("Camera.jitter must be finite, got ", text(jitter)));
    const glm::dvec3 forward = glm::dvec3(target) - glm::dvec3(position);
    if (!(glm::length(forward) > 0.0))
        throw Error(str("Camera.position ", text(position), " is its target: no view direction"));
    if (!(glm::length(glm::cross(glm::normalize(forward), glm::dvec3(up))) > 1e-6 * glm::length(glm::dvec3(up))))
        throw Error(str("Camera.up ", text(up), " is not across the view direction ", text(glm::vec3(forward)),
                        " (or is zero): no roll to look with"));
    if (!(fovY > 0.0f && fovY < 3.14159265f)) throw Error(str("Camera.fovY must be in (0, pi) radians, got ", fovY));
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) throw Error(str("Camera.aspect must be positive, got ", aspect));
    if (!(nearPlane > 0.0f && nearPlane < farPlane) || !std::isfinite(farPlane))
        throw Error(str("Camera needs 0 < nearPlane < farPlane, both finite, got ", nearPlane, " and ", farPlane));
    if (previousViewProjection && !isFinite(*previousViewProjection))
        throw Error("Camera.previousViewProjection must be finite");
    if (!customProjection) return;
    const glm::mat4& p = *customProjection;
    if (!isFinite(p)) throw Error("Camera.customProjection must be finite");
    const glm::vec4 lastRow(p[0][3], p[1][3], p[2][3], p[3][3]);
    const bool ortho = orthographic();
    if (!ortho && glm::length(lastRow - glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)) > 1e-6f)
        throw Error(str("Camera.customProjection must be a perspective projection, its last row (0, 0, -1, 0) (w the "
                        "distance in front of the eye), or an orthographic one, (0, 0, 0, 1); got ", text(lastRow)));
    if (!(std::abs(glm::determinant(glm::dmat4(p))) > 0.0)) throw Error("Camera.customProjection has no inverse");
    // Along the view axis (z = -distance) the clip depth is -p22 + p32 / distance for a
    // perspective: it grows with the distance where p32 < 0 (GL's default), shrinks where p32 > 0
    // (reversed); for an orthographic one it is -p22 distance + p32: it grows where p22 < 0.
    const bool reversed = ortho ? p[2][2] > 0.0f : p[3][2] > 0.0f;
    if (reversed != reversedZ)
        throw Error(str("Camera.customProjection maps depth ", reversed ? "reversed (near at the larger depth)" : "GL's default way (near at the smaller depth)",
                        ", but Camera.reversedZ is ", reversedZ ? "true" : "false"));
}

namespace {
/// The eye's x axis flipped: a mirror's view is lookAt's followed by it.
glm::mat4 flipEyeX(const glm::mat4& view) { return glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)) * view; }
} // namespace

bool Camera::orthographic() const {
    if (!customProjection) return false;
    const glm::mat4& p = *customProjection;
    return glm::length(glm::vec4(p[0][3], p[1][3], p[2][3], p[3][3]) - glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)) <= 1e-6f;
}

glm::mat4 Camera::view() const {
    const glm::mat4 v = glm::lookAt(position, target, up);
    return mirrored ? flipEyeX(v) : v;
}

glm::mat4 Camera::projection() const {
    // Reversed Z: [0, 1] clip depth with the planes swapped, near at 1 and far at 0.
    const glm::mat4 p = customProjection ? *customProjection
                        : reversedZ      ? glm::perspectiveRH_ZO(fovY, aspect, farPlane, nearPlane)
                                         : glm::perspective(fovY, aspect, nearPlane, farPlane);
    if (jitter == glm::vec2(0.0f)) return p;
    // x' = x + jitter.x * w in clip space: the image moves by jitter in NDC.
    return glm::translate(glm::mat4(1.0f), glm::vec3(jitter, 0.0f)) * p;
}

glm::mat4 Camera::unjitteredViewProjection() const {
    Camera still = *this;
    still.jitter = glm::vec2(0.0f);
    return still.viewProjection();
}

Ray Camera::rayThroughPixel(double x, double y, int width, int height) const {
    const glm::dmat4 viewProj = glm::dmat4(projection()) * glm::dmat4(view());
    const glm::dmat4 inverse = glm::inverse(viewProj);
    const double ndcX = 2.0 * x / width - 1.0, ndcY = 2.0 * y / height - 1.0;
    glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, reversedZ ? 1.0 : -1.0, 1.0);
    glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, reversedZ ? 0.0 : 1.0, 1.0);
    nearPoint /= nearPoint.w;
    farPoint /= farPoint.w;
    // Away from the eye, where clip w grows: an oblique near plane's tilted far plane lies behind
    // the eye for some rays (past infinity), and the far point less the near one points back.
    glm::dvec3 along(farPoint - nearPoint);
    if (glm::dot(glm::dvec3(viewProj[0][3], viewProj[1][3], viewProj[2][3]), along) < 0.0) along = -along;
    return {orthographic() ? glm::dvec3(nearPoint) : glm::dvec3(position), glm::normalize(along)};
}

float Camera::nearPlaneReach() const {
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(projection()));
    double reach = 0.0;
    for (const double x : {-1.0, 1.0})
        for (const double y : {-1.0, 1.0}) {
            const glm::dvec4 corner = inverse * glm::dvec4(x, y, reversedZ ? 1.0 : -1.0, 1.0);
            reach = std::max(reach, glm::length(glm::dvec3(corner) / corner.w));
        }
    return float(reach);
}

Camera Camera::fromMatrices(const glm::mat4& view, const glm::mat4& projection, bool reversedZ) {
    if (!isFinite(view)) throw Error("Camera::fromMatrices: the view must be finite");
    // Rigid: orthonormal columns of its 3x3 part, and no projective row.
    const glm::dmat3 r{glm::dmat4(view)};
    const glm::dmat3 gram = glm::transpose(r) * r;
    double off = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) off = std::max(off, std::abs(gram[i][j] - (i == j ? 1.0 : 0.0)));
    const glm::vec4 lastRow(view[0][3], view[1][3], view[2][3], view[3][3]);
    if (off > 1e-4 || lastRow != glm::vec4(0.0f, 0.0f, 0.0f, 1.0f))
        throw Error(str("Camera::fromMatrices: the view must be rigid (a rotation or a reflection, and a translation: "
                        "no scale, shear or projection), got axes of lengths ", glm::length(r[0]), ", ",
                        glm::length(r[1]), ", ", glm::length(r[2]), " and a last row ", text(lastRow)));
    Camera c;
    c.mirrored = glm::determinant(r) < 0.0;
    const glm::mat4 world = glm::inverse(c.mirrored ? flipEyeX(view) : view);
    c.position = glm::vec3(world[3]);
    c.target = c.position - glm::vec3(world[2]); // the eye looks down its -z
    c.up = glm::vec3(world[1]);
    c.reversedZ = reversedZ;
    c.customProjection = projection;
    return c;
}

Camera Camera::orbit(glm::vec3 target, float distance, float azimuth, float elevation) {
    Camera c;
    c.target = target;
    c.position = target + distance * glm::vec3(std::cos(elevation) * std::sin(azimuth),
                                                std::sin(elevation),
                                                std::cos(elevation) * std::cos(azimuth));
    return c;
}

namespace {

/// Sutherland-Hodgman: the part of `polygon` where distance(point) >= 0 (a plane's signed
/// distance, linear in the point, so the crossing is where it interpolates to 0).
template <typename Distance>
std::vector<glm::dvec4> clipPolygon(const std::vector<glm::dvec4>& polygon, Distance&& distance) {
    std::vector<glm::dvec4> out;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec4& a = polygon[i];
        const glm::dvec4& b = polygon[(i + 1) % polygon.size()];
        const double da = distance(a), db = distance(b);
        if (da >= 0.0) out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

} // namespace

double screenArea(std::span<const glm::vec3> polygon, const glm::mat4& viewProjection, int width, int height) {
    const glm::dmat4 m(viewProjection);
    std::vector<glm::dvec4> clip;
    for (const glm::vec3& p : polygon) clip.push_back(m * glm::dvec4(glm::dvec3(p), 1.0));
    // In clip space, before the divide, so a polygon through the camera's plane clips right: the
    // near and far planes (either convention's, above), then the image's four edges (-w <= x, y <= w,
    // which also leave w > 0 only).
    clip = clipPolygon(clip, [](const glm::dvec4& c) { return c.z + c.w; });
    clip = clipPolygon(clip, [](const glm::dvec4& c) { return c.w - c.z; });
    clip = clipPolygon(clip, [](const glm::dvec4& c) { return c.w - c.x; });
    clip = clipPolygon(clip, [](const glm::dvec4& c) { return c.w + c.x; });
    clip = clipPolygon(clip, [](const glm::dvec4& c) { return c.w - c.y; });
    clip = clipPolygon(clip, [](const glm::dvec4& c) { return c.w + c.y; });
    double twiceArea = 0.0; // in normalized device coordinates (the image is 2 x 2)
    for (size_t i = 0; i < clip.size(); ++i) {
        const glm::dvec4& a = clip[i];
        const glm::dvec4& b = clip[(i + 1) % clip.size()];
        twiceArea += a.x / a.w * (b.y / b.w) - b.x / b.w * (a.y / a.w);
    }
    return std::abs(twiceArea) * 0.5 * (0.25 * double(width) * double(height));
}

} // namespace hfx
