#include "hfx/core/Camera.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>

namespace hfx {

glm::mat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::projection() const {
    return glm::perspective(fovY, aspect, nearPlane, farPlane);
}

Ray Camera::rayThroughPixel(double x, double y, int width, int height) const {
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(projection()) * glm::dmat4(view()));
    const double ndcX = 2.0 * x / width - 1.0, ndcY = 2.0 * y / height - 1.0;
    glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
    glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    nearPoint /= nearPoint.w;
    farPoint /= farPoint.w;
    return {glm::dvec3(position), glm::normalize(glm::dvec3(farPoint - nearPoint))};
}

Camera Camera::orbit(glm::vec3 target, float distance, float azimuth, float elevation) {
    Camera c;
    c.target = target;
    c.position = target + distance * glm::vec3(std::cos(elevation) * std::sin(azimuth),
                                                std::sin(elevation),
                                                std::cos(elevation) * std::cos(azimuth));
    return c;
}

} // namespace hfx
