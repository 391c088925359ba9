#include "online/window/window.h"

#include <GLFW/glfw3.h>

#include "models/core/error.h"

namespace coif::gl {
namespace {

Error window_error(const std::string& what) {
    const char* msg = nullptr;
    glfwGetError(&msg);
    return Error::parameter("OpenGL", what + ": " + (msg ? msg : "unknown"));
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
    if (!glfwInit()) throw window_error("cannot start GLFW (no display? run under xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const Error e = window_error("cannot open an OpenGL 4.5 core window");
        glfwTerminate();
        throw e;
    }
    make_current();
    glfwSwapInterval(0);
}

Window::~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

void Window::make_current() { glfwMakeContextCurrent(window_); }

}  // namespace coif::gl
