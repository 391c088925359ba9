#pragma once
// Thin RAII owners of GL objects and the program builder. Everything GL in coif goes through
// online/; models/, shaders/ (C++ side), offline/ and db/ never include GL.
#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "models/core/image.h"
#include "shaders/lut.h"

namespace coif::gl {

// Owns one GL object name; `Deleter` frees it.
template <void (*Deleter)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) { reset(); id_ = std::exchange(o.id_, 0); }
        return *this;
    }
    GLuint id() const { return id_; }
    void reset() { if (id_) Deleter(id_); id_ = 0; }

private:
    GLuint id_ = 0;
};

void delete_buffer(GLuint id);
void delete_vertex_array(GLuint id);
void delete_texture(GLuint id);
void delete_framebuffer(GLuint id);
void delete_renderbuffer(GLuint id);
void delete_program(GLuint id);
void delete_query(GLuint id);

using Buffer = Handle<delete_buffer>;
using VertexArray = Handle<delete_vertex_array>;
using Texture = Handle<delete_texture>;
using Framebuffer = Handle<delete_framebuffer>;
using Renderbuffer = Handle<delete_renderbuffer>;
using ProgramHandle = Handle<delete_program>;
using Query = Handle<delete_query>;

Buffer make_buffer(const void* data, size_t bytes, GLbitfield flags = 0);
VertexArray make_vertex_array();
// Draws one full-screen triangle (fullscreen.vert; `empty_vao`: a vertex array with no attributes) with the program in
// use into the bound framebuffer's viewport: replacing its pixels, or with `over` blended premultiplied "over" them
// (ONE, ONE_MINUS_SRC_ALPHA, with GL_FRAMEBUFFER_SRGB on, so an sRGB target blends linearly). Depth test, face culling,
// blending and GL_FRAMEBUFFER_SRGB are off afterwards. The compositing resolves' last step (online/fragment_lists.h,
// online/weighted_blend.h).
void draw_fullscreen_into_frame(const VertexArray& empty_vao, bool over);
// Enables float attribute `location` of `vao`: `components` floats at `offset` in the vertex buffer
// bound to `binding`.
void float_attribute(GLuint vao, GLuint location, GLint components, std::size_t offset, GLuint binding);
// How a texture is sampled: one filter for minification and magnification (no mipmaps), one wrap mode
// for every axis (GL_CLAMP_TO_BORDER borders are zero).
struct Sampling {
    GLenum filter = GL_LINEAR;
    GLenum wrap = GL_CLAMP_TO_EDGE;
};
// Immutable storage of one level; `sampling` set when given (else GL's defaults, for image-only use).
Texture make_texture_2d(GLenum internal_format, int width, int height, std::optional<Sampling> sampling = std::nullopt);
Texture make_texture_3d(GLenum internal_format, glm::ivec3 size, std::optional<Sampling> sampling = std::nullopt);
// A 2D array texture of `layers` layers (image-only use: GL's default sampling).
Texture make_texture_2d_array(GLenum internal_format, int width, int height, int layers);
// Sets the filter and wrap of `texture` (2D or 3D).
void set_sampling(const Texture& texture, Sampling sampling);

// A lighting table (shaders/lut.h) as an RGBA32F texture with linear filtering and clamped edges,
// the sampling its C++ twin reproduces.
Texture make_lut_texture(const shading::LutImage& image);

// The text of a GLSL file under shaders/, compiled into the binary; throws coif::Error if unknown.
std::string shader_text(const std::string& path);

// Links a program from GLSL files under shaders/ (paths like "shaders/gl/strand_lines.vert"),
// stage chosen by extension (.vert .frag .comp). Each source gets "#version 450 core", the
// defines, shaders/gl/prelude.glsl, then its text with every `#include "shaders/…"` line replaced
// by that file (once per program). Compile/link errors throw coif::Error with the log.
// Seconds spent compiling and linking programs in this process so far (Program's constructor), so that load times
// can be reported apart from shader compilation.
double program_compile_seconds();

class Program {
public:
    Program() = default;
    Program(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});
    GLuint id() const { return handle_.id(); }
    GLint uniform(const char* name) const { return glGetUniformLocation(handle_.id(), name); }
    void use() const { glUseProgram(handle_.id()); }

private:
    ProgramHandle handle_;
};

// An offscreen colour (+ depth) target, optionally multisampled and resolved on read-back.
class RenderTarget {
public:
    RenderTarget(int width, int height, GLenum color_format = GL_RGBA16F, int samples = 1);
    void bind() const;
    // Resolves the samples (if multisampled) and returns a single-sample framebuffer holding the image.
    GLuint resolve() const;
    // Resolves and reads the colour attachment back as a linear RGBA image, row 0 at the top.
    Image read_back() const;
    int width() const { return width_; }
    int height() const { return height_; }
    GLuint framebuffer() const { return fbo_.id(); }

private:
    int width_, height_, samples_;
    GLenum format_;
    Framebuffer fbo_, resolve_fbo_;
    Renderbuffer color_, depth_;
    Texture resolve_color_;
};

// Throws coif::Error if glGetError reports something, naming `where`.
void check_errors(const char* where);

}  // namespace coif::gl
