// coif view — the interactive viewer (GLFW window). Current state: the strand preview with an orbit
// camera; appearance editing arrives with the renderer.
#include <GLFW/glfw3.h>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <memory>

#include "models/core/error.h"
#include "online/gl_context.h"
#include "online/strand_preview.h"
#include "tools/cli.h"
#include "tools/scene_options.h"

namespace {

struct ViewOptions {
    coif::cli::SceneOptions scene;
    int frames = 0;
    std::string screenshot;
};

struct Orbit {
    double azimuth, elevation, distance_scale = 1.0;
    bool dragging = false;
    double last_x = 0, last_y = 0;
};

void add_view(CLI::App& root) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* view = root.add_subcommand(
        "view",
        "Open the interactive viewer in a window\n"
        "It needs a display: use `xvfb-run -a coif view` without one.\n"
        "Drag with the left mouse button to orbit, scroll to zoom, Esc or Q to quit.\n"
        "Current state: strands drawn with the preview shading (see `coif render --help`).");
    o->scene.add_to(view);
    view->add_option("--frames", o->frames, "Quit after this many frames (0 = run until closed); for scripts and tests")
        ->check(CLI::NonNegativeNumber);
    view->add_option("--screenshot", o->screenshot, "Write the last frame to this image (.png/.exr) when the viewer quits");
    coif::cli::examples(view, "  coif view\n  coif view --strands ../shared/data/harolongo.data\n"
                              "  xvfb-run -a coif view --frames 3 --screenshot shot.png");
    view->callback([o] {
        const coif::Strands strands = o->scene.load_strands();
        const auto box = o->scene.frame_box(strands);
        auto context = coif::gl::Context::window(o->scene.width, o->scene.height, "coif view");
        GLFWwindow* window = context->glfw_window();
        coif::gl::StrandPreview preview(strands);
        Orbit orbit{o->scene.azimuth_deg, o->scene.elevation_deg};
        glfwSetWindowUserPointer(window, &orbit);
        glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
            auto* orb = static_cast<Orbit*>(glfwGetWindowUserPointer(w));
            orb->distance_scale = std::clamp(orb->distance_scale * std::pow(0.9, dy), 0.1, 10.0);
        });
        std::unique_ptr<coif::gl::RenderTarget> target;
        const coif::gl::StrandPreviewSettings settings;
        for (int frame = 0; !glfwWindowShouldClose(window) && (o->frames == 0 || frame < o->frames); ++frame) {
            glfwPollEvents();
            if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS || glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS) break;
            double x, y;
            glfwGetCursorPos(window, &x, &y);
            const bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
            if (down && orbit.dragging) {
                orbit.azimuth -= 0.4 * (x - orbit.last_x);
                orbit.elevation = std::clamp(orbit.elevation + 0.4 * (y - orbit.last_y), -89.0, 89.0);
            }
            orbit.dragging = down;
            orbit.last_x = x;
            orbit.last_y = y;

            int fb_w, fb_h;
            glfwGetFramebufferSize(window, &fb_w, &fb_h);
            if (fb_w <= 0 || fb_h <= 0) continue;  // minimised
            coif::cli::SceneOptions so = o->scene;
            so.width = fb_w;
            so.height = fb_h;
            so.azimuth_deg = orbit.azimuth;
            so.elevation_deg = orbit.elevation;
            coif::Camera camera = so.camera_around(box);
            camera.eye = camera.target + float(orbit.distance_scale) * (camera.eye - camera.target);
            camera.near_plane *= float(orbit.distance_scale);
            camera.far_plane *= float(orbit.distance_scale);

            if (!target || target->width() != fb_w || target->height() != fb_h)
                target = std::make_unique<coif::gl::RenderTarget>(fb_w, fb_h, GL_RGBA16F, settings.samples);
            target->bind();
            glClearColor(settings.background.x, settings.background.y, settings.background.z, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            preview.draw(camera, settings);
            // Show it: resolve the samples, then copy into the window (linear values; preview only).
            glBlitNamedFramebuffer(target->resolve(), 0, 0, 0, fb_w, fb_h, 0, 0, fb_w, fb_h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glfwSwapBuffers(window);
        }
        if (!o->screenshot.empty()) {
            if (!target) throw coif::Error(o->screenshot, "", "no frame was drawn, so there is nothing to save");
            coif::WriteOptions wo;
            wo.description = coif::gl::kStrandPreviewLabel;
            coif::write_image(o->screenshot, target->read_back(), wo);
            std::fprintf(stderr, "wrote %s\n", o->screenshot.c_str());
        }
    });
}

COIF_REGISTER_COMMAND(70, add_view);

}  // namespace
