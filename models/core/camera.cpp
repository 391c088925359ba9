#include "models/core/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace coif {

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projection() const { return glm::perspective(fov_y, aspect(), near_plane, far_plane); }

glm::vec2 Camera::pixel(glm::vec3 p) const {
    const glm::vec4 c = projection() * view() * glm::vec4(p, 1.0f);
    return {(c.x / c.w + 1.0f) * 0.5f * float(width), (1.0f - c.y / c.w) * 0.5f * float(height)};
}

void Camera::ray(float px, float py, glm::vec3& origin, glm::vec3& direction) const {
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    const glm::vec3 true_up = glm::cross(right, forward);
    const float half_h = std::tan(fov_y * 0.5f);
    const float sx = (2.0f * px / float(width) - 1.0f) * half_h * aspect();
    const float sy = (1.0f - 2.0f * py / float(height)) * half_h;
    origin = eye;
    direction = glm::normalize(forward + sx * right + sy * true_up);
}

Camera Camera::orbit(const glm::vec3& box_min, const glm::vec3& box_max, float azimuth, float elevation, int width,
                     int height, float fov_y) {
    Camera c;
    c.width = width;
    c.height = height;
    c.fov_y = fov_y;
    c.target = 0.5f * (box_min + box_max);
    const float radius = 0.5f * glm::length(box_max - box_min);
    const float half_fov = 0.5f * std::min(fov_y, 2.0f * std::atan(std::tan(0.5f * fov_y) * c.aspect()));
    const float distance = 1.1f * radius / std::sin(half_fov);
    const glm::vec3 dir(std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth));
    c.eye = c.target + distance * dir;
    c.near_plane = std::max(1e-3f, distance - 2.0f * radius);
    c.far_plane = distance + 2.0f * radius;
    return c;
}

}  // namespace coif
