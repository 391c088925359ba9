#pragma once
// A window with a current OpenGL 4.5 core context (GLFW). It needs a display: under `xvfb-run -a` without
// one. The only GLFW user of coif, with the viewer drawn in it (online/window/viewer.h); offscreen rendering
// needs none of it (online/gl_context.h).
#include <string>

struct GLFWwindow;

namespace coif::gl {

class Window {
public:
    // Opens the window and makes its context current, vsync off; throws coif::Error when GLFW cannot start
    // (no display) or the driver offers no 4.5 core context.
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    void make_current();
    GLFWwindow* glfw() const { return window_; }  // for input and callbacks (the viewer)

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace coif::gl
