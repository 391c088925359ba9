#include <gtest/gtest.h>

#include "models/core/camera.h"

namespace coif {
namespace {

// Camera::pixel is ray's inverse: a point on the ray through image point (px, py) projects back to it, for points at
// several depths and image points across the frame (tolerance: float rounding of the projection, 1e-3 px).
TEST(Camera, PixelIsTheInverseOfRay) {
    const Camera camera = Camera::orbit(glm::vec3(-3.0f, -10.0f, -2.0f), glm::vec3(4.0f, 1.0f, 3.0f), 0.7f, -0.3f, 320, 200);
    for (const glm::vec2 q : {glm::vec2(0.0f, 0.0f), glm::vec2(160.0f, 100.0f), glm::vec2(319.5f, 12.25f), glm::vec2(7.0f, 199.0f)})
        for (const float t : {1.0f, 10.0f, 60.0f}) {
            glm::vec3 o, d;
            camera.ray(q.x, q.y, o, d);
            const glm::vec2 back = camera.pixel(o + t * d);
            EXPECT_NEAR(back.x, q.x, 1e-3f) << q.x << ", " << q.y << " at " << t;
            EXPECT_NEAR(back.y, q.y, 1e-3f) << q.x << ", " << q.y << " at " << t;
        }
}

}  // namespace
}  // namespace coif
