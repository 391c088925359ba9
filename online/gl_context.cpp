#include "online/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <cstdio>
#include <vector>

#include "models/core/error.h"

namespace coif::gl {
namespace {

Error context_error(const std::string& what) { return Error::parameter("OpenGL", what); }

std::string egl_error_hex() {
    char b[16];
    std::snprintf(b, sizeof b, "0x%x", static_cast<unsigned>(eglGetError()));
    return b;
}

bool has_extension(const char* list, const char* name) {
    if (!list) return false;
    const std::string all = std::string(" ") + list + " ";
    return all.find(std::string(" ") + name + " ") != std::string::npos;
}

EGLDisplay open_display(std::string& platform) {
    const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (has_extension(client_ext, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
            platform = "EGL surfaceless";
            return d;
        }
    }
    if (has_extension(client_ext, "EGL_EXT_platform_device") && has_extension(client_ext, "EGL_EXT_device_enumeration")) {
        EGLint count = 0;
        eglQueryDevicesEXT(0, nullptr, &count);
        std::vector<EGLDeviceEXT> devices(static_cast<size_t>(std::max(count, 0)));
        if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count)) {
            for (EGLDeviceEXT device : devices) {
                EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
                if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
                    platform = "EGL device";
                    return d;
                }
            }
        }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
        platform = "EGL default display";
        return d;
    }
    throw context_error("no EGL display could be initialised (is Mesa's libegl-mesa0 installed?)");
}

}  // namespace

std::unique_ptr<Context> Context::headless() {
    std::unique_ptr<Context> c(new Context);
    EGLDisplay display = open_display(c->platform_);
    c->display_ = display;
    if (!eglBindAPI(EGL_OPENGL_API)) throw context_error("EGL cannot bind the desktop OpenGL API");
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint n = 0;
    const bool have_config = eglChooseConfig(display, config_attribs, &config, 1, &n) && n > 0;
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    // Surfaceless contexts need no config (EGL_KHR_no_config_context) when none is offered.
    EGLContext ctx = eglCreateContext(display, have_config ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
    if (ctx == EGL_NO_CONTEXT)
        throw context_error("cannot create an OpenGL 4.5 core context through " + c->platform_ +
                            " (EGL error " + egl_error_hex() + ")");
    c->context_ = ctx;
    c->make_current();
    return c;
}

Context::~Context() {
    if (display_) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_) eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
}

void Context::make_current() {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) throw context_error("eglMakeCurrent failed");
}

void Context::finish() const { glFinish(); }

std::string Context::renderer() const {
    const auto* s = glGetString(GL_RENDERER);
    return s ? reinterpret_cast<const char*>(s) : "unknown";
}

std::string Context::version() const {
    const auto* s = glGetString(GL_VERSION);
    return s ? reinterpret_cast<const char*>(s) : "unknown";
}

}  // namespace coif::gl
