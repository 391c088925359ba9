#include "online/window/viewer.h"

#include <GLFW/glfw3.h>
#include <algorithm>
#include <cmath>
#include <memory>

#include "online/gl.h"
#include "online/window/window.h"

namespace coif::gl {
namespace {

// Orbit per pixel of mouse drag, and the elevation's limit (short of the poles, where the y-up camera turns over).
const double kDragRadiansPerPixel = glm::radians(0.4);
const double kMaxElevation = glm::radians(89.0);
// Each scroll step moves the eye 10% nearer (or farther), within [0.1, 10] times the framing distance.
constexpr double kZoomPerStep = 0.9, kMinZoom = 0.1, kMaxZoom = 10.0;

struct Orbit {
    double azimuth, elevation, distance_scale = 1.0;
    bool dragging = false;
    double last_x = 0, last_y = 0;
};

}  // namespace

ViewerResult run_viewer(const ViewerOptions& o) {
    Window window(o.view.width, o.view.height, "coif view");
    GLFWwindow* w = window.glfw();
    StrandPreview preview(o.strands);
    Orbit orbit{o.view.azimuth, o.view.elevation};
    glfwSetWindowUserPointer(w, &orbit);
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
        auto* orb = static_cast<Orbit*>(glfwGetWindowUserPointer(win));
        orb->distance_scale = std::clamp(orb->distance_scale * std::pow(kZoomPerStep, dy), kMinZoom, kMaxZoom);
    });
    std::unique_ptr<RenderTarget> target;
    ViewerResult result;
    for (; !glfwWindowShouldClose(w) && (o.frames == 0 || result.frames < o.frames); ++result.frames) {
        glfwPollEvents();
        if (glfwGetKey(w, GLFW_KEY_ESCAPE) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_Q) == GLFW_PRESS) break;
        double x, y;
        glfwGetCursorPos(w, &x, &y);
        const bool down = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        if (down && orbit.dragging) {
            orbit.azimuth -= kDragRadiansPerPixel * (x - orbit.last_x);
            orbit.elevation = std::clamp(orbit.elevation + kDragRadiansPerPixel * (y - orbit.last_y), -kMaxElevation,
                                         kMaxElevation);
        }
        orbit.dragging = down;
        orbit.last_x = x;
        orbit.last_y = y;

        int fb_w, fb_h;
        glfwGetFramebufferSize(w, &fb_w, &fb_h);
        if (fb_w <= 0 || fb_h <= 0) continue;  // minimised
        OrbitView view = o.view;
        view.width = fb_w;
        view.height = fb_h;
        view.azimuth = static_cast<float>(orbit.azimuth);
        view.elevation = static_cast<float>(orbit.elevation);
        Camera camera = view.around(o.frame_min, o.frame_max);
        camera.eye = camera.target + float(orbit.distance_scale) * (camera.eye - camera.target);
        camera.near_plane *= float(orbit.distance_scale);
        camera.far_plane *= float(orbit.distance_scale);

        if (!target || target->width() != fb_w || target->height() != fb_h)
            target = std::make_unique<RenderTarget>(fb_w, fb_h, GL_RGBA16F, o.preview.samples);
        target->bind();
        glClearColor(o.preview.background.x, o.preview.background.y, o.preview.background.z, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        preview.draw(camera, o.preview);
        // Show it: resolve the samples, then copy into the window (linear values; preview only).
        glBlitNamedFramebuffer(target->resolve(), 0, 0, 0, fb_w, fb_h, 0, 0, fb_w, fb_h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glfwSwapBuffers(w);
    }
    if (o.keep_last_frame && target) result.last_frame = target->read_back();
    return result;
}

}  // namespace coif::gl
