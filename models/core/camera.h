#pragma once
// The one camera model of coif, shared by the GL renderer and the CPU reference renderer so that
// both see exactly the same pixels. A pinhole camera: `eye` looks at `target`, `up` is +y (coif
// scenes are y-up), vertical field of view `fov_y` (radians). Image pixel (x, y) has its centre at
// (x + 0.5, y + 0.5), y = 0 at the TOP row, matching coif::Image. Projection follows OpenGL
// (right-handed eye space looking down −z, clip z in [−w, w]).
#include <glm/glm.hpp>

namespace coif {

// Linear RGB behind the hair in every renderer's image unless a command is given --background (a dark
// blue-grey, so that dark hair stands out).
inline constexpr glm::vec3 kDefaultBackground{0.05f, 0.05f, 0.06f};

struct Camera {
    glm::vec3 eye{0, 0, 50};
    glm::vec3 target{0};
    glm::vec3 up{0, 1, 0};
    float fov_y = 0.6981317f;  // 40°
    float near_plane = 0.1f;
    float far_plane = 1000.0f;
    int width = 720;
    int height = 480;

    float aspect() const { return float(width) / float(height); }
    glm::mat4 view() const;
    glm::mat4 projection() const;
    // World-space ray through a point of the image in pixel units (x right, y down, (0,0) top-left corner).
    void ray(float px, float py, glm::vec3& origin, glm::vec3& direction) const;
    // The point of the image, in ray's pixel units, where world point p (in front of the eye) projects.
    glm::vec2 pixel(glm::vec3 p) const;

    // A camera orbiting a bounding box: azimuth about +y measured from +z towards +x, elevation
    // above the horizontal plane (both radians); the distance frames the whole box with a margin.
    static Camera orbit(const glm::vec3& box_min, const glm::vec3& box_max, float azimuth, float elevation,
                        int width, int height, float fov_y = 0.6981317f);
};

// Everything Camera::orbit takes but the box: how a scene's camera is placed around whatever it frames.
struct OrbitView {
    float azimuth = 0.0f, elevation = 0.0f;  // radians, as Camera::orbit
    int width = 720, height = 480;
    float fov_y = 0.6981317f;  // 40°

    Camera around(const glm::vec3& box_min, const glm::vec3& box_max) const {
        return Camera::orbit(box_min, box_max, azimuth, elevation, width, height, fov_y);
    }
};

}  // namespace coif
