#pragma once
// Headless OpenGL 4.5 core contexts. This module (with online/gl.h) owns every GL call of coif: no other
// folder includes GL. (A window with its context is online/window/window.h, a library of its own, so that a
// program drawing hair offscreen links no window system.)
//
// headless() is EGL without any window system. It tries, in order, Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless: llvmpipe on machines without a GPU, no X needed), the EGL device platform
// (EGL_EXT_platform_device: NVIDIA's headless driver) and the default display. Rendering goes to framebuffer
// objects. Function pointers are loaded by libepoxy for whichever context is current.
#include <memory>
#include <string>

namespace coif::gl {

class Context {
public:
    static std::unique_ptr<Context> headless();
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    void make_current();
    // Waits until the GL commands issued so far have finished (glFinish): what a wall-clock timing of GPU work
    // ends with.
    void finish() const;
    std::string renderer() const;   // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version() const;    // GL_VERSION
    std::string platform() const { return platform_; }  // how the context was made, in words

private:
    Context() = default;
    void* display_ = nullptr;  // EGLDisplay
    void* context_ = nullptr;  // EGLContext
    std::string platform_;
};

}  // namespace coif::gl
