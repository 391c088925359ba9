#include "online/gl.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "models/core/error.h"
#include "online/shader_files.h"

namespace coif::gl {

void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
void delete_program(GLuint id) { glDeleteProgram(id); }
void delete_query(GLuint id) { glDeleteQueries(1, &id); }

namespace {
std::string error_code(GLenum e) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", e);
    return code;
}
}  // namespace

void check_errors(const char* where) {
    const GLenum e = glGetError();
    if (e != GL_NO_ERROR) throw Error::parameter("OpenGL", "error " + error_code(e) + " in " + where);
}

namespace {
// A storage allocation that the GPU refused (GL_OUT_OF_MEMORY, or a size over its limits) is an error naming
// the size, raised where it happens: never a texture or buffer that silently holds nothing.
void check_allocation(const std::string& what) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) return;
    throw Error::parameter("OpenGL", e == GL_OUT_OF_MEMORY ? "out of GPU memory for " + what
                                                           : "cannot allocate " + what + " (error " + error_code(e) + ")");
}

void check_side(const char* kind, GLenum limit_name, std::initializer_list<int> sides) {
    GLint limit = 0;
    glGetIntegerv(limit_name, &limit);
    std::string size;
    bool over = false;
    for (int side : sides) {
        if (!size.empty()) size += 'x';
        size += std::to_string(side);
        over = over || side < 1 || side > limit;
    }
    if (over)
        throw Error::parameter("OpenGL", std::string("a ") + size + " " + kind + " texture is outside this GPU's limit of 1.." +
                                             std::to_string(limit) + " texels per side");
}
}  // namespace

Buffer make_buffer(const void* data, size_t bytes, GLbitfield flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Buffer b(id);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(std::max<size_t>(bytes, 1)), data, flags);
    check_allocation("a " + std::to_string(bytes) + "-byte buffer");
    return b;
}

void set_sampling(const Texture& texture, Sampling sampling) {
    const GLuint id = texture.id();
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(sampling.filter));
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(sampling.filter));
    for (const GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(id, axis, static_cast<GLint>(sampling.wrap));
    if (sampling.wrap == GL_CLAMP_TO_BORDER) {
        const float zero[4] = {0, 0, 0, 0};
        glTextureParameterfv(id, GL_TEXTURE_BORDER_COLOR, zero);
    }
}

Texture make_texture_2d(GLenum internal_format, int width, int height, std::optional<Sampling> sampling) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    Texture t(id);
    check_side("2D", GL_MAX_TEXTURE_SIZE, {width, height});
    glTextureStorage2D(id, 1, internal_format, width, height);
    check_allocation("a " + std::to_string(width) + "x" + std::to_string(height) + " texture");
    if (sampling) set_sampling(t, *sampling);
    return t;
}

Texture make_texture_2d_array(GLenum internal_format, int width, int height, int layers) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    Texture t(id);
    check_side("2D", GL_MAX_TEXTURE_SIZE, {width, height});
    check_side("array", GL_MAX_ARRAY_TEXTURE_LAYERS, {layers});
    glTextureStorage3D(id, 1, internal_format, width, height, layers);
    check_allocation("a " + std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(layers) + " array texture");
    return t;
}

Texture make_texture_3d(GLenum internal_format, glm::ivec3 size, std::optional<Sampling> sampling) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &id);
    Texture t(id);
    check_side("3D", GL_MAX_3D_TEXTURE_SIZE, {size.x, size.y, size.z});
    glTextureStorage3D(id, 1, internal_format, size.x, size.y, size.z);
    check_allocation("a " + std::to_string(size.x) + "x" + std::to_string(size.y) + "x" + std::to_string(size.z) + " texture");
    if (sampling) set_sampling(t, *sampling);
    return t;
}

Texture make_lut_texture(const shading::LutImage& img) {
    Texture t = make_texture_2d(GL_RGBA32F, img.width, img.height, Sampling{GL_LINEAR, GL_CLAMP_TO_EDGE});
    glTextureSubImage2D(t.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, img.texels.data());
    return t;
}

VertexArray make_vertex_array() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return VertexArray(id);
}

void draw_fullscreen_into_frame(const VertexArray& empty_vao, bool over) {
    if (over) {  // premultiplied "over" the frame; an sRGB target encodes the blended linear result
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        glEnable(GL_FRAMEBUFFER_SRGB);
    } else {
        glDisable(GL_BLEND);
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(empty_vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
}

void float_attribute(GLuint vao, GLuint location, GLint components, std::size_t offset, GLuint binding) {
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribFormat(vao, location, components, GL_FLOAT, GL_FALSE, static_cast<GLuint>(offset));
    glVertexArrayAttribBinding(vao, location, binding);
}

std::string shader_text(const std::string& path) {
    const auto bytes = embedded::shader_file(path);
    if (!bytes) throw Error(path, "", "no such shader file compiled into coif");
    return std::string(reinterpret_cast<const char*>(bytes->data()), bytes->size());
}

namespace {

// Writes `path` to `out` with its #include lines replaced by the files they name, recursively. A file is written at
// every #include of it: each shader file is include-guarded (shaders/glsl_prelude.h), so GLSL's preprocessor keeps the
// first copy that a program's defines compile in. (Writing a file only at its first #include lost it from a variant
// whose first #include of it sits in an #if that is off there, such as own_cluster.glsl's includes under SHELL_OWN 0.)
// `stack` holds the files being expanded, to refuse a cycle.
void expand_includes(const std::string& path, std::vector<std::string>& stack, std::ostringstream& out) {
    if (std::find(stack.begin(), stack.end(), path) != stack.end()) {
        std::string chain;
        for (const std::string& f : stack) chain += f + " -> ";
        throw Error(path, "", "#include cycle: " + chain + path);
    }
    if (stack.size() > 16) throw Error(path, "", "#include nesting deeper than 16");
    stack.push_back(path);
    std::istringstream in(shader_text(path));
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        const auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.compare(first, 8, "#include") == 0) {
            const auto a = line.find('"'), b = line.rfind('"');
            if (a == std::string::npos || b <= a) throw Error(path, "line " + std::to_string(number), "malformed #include");
            expand_includes(line.substr(a + 1, b - a - 1), stack, out);
            out << "\n";
            continue;
        }
        out << line << "\n";
    }
    stack.pop_back();
}

GLuint compile(const std::string& path, const std::vector<std::string>& defines) {
    GLenum stage;
    if (path.ends_with(".vert")) stage = GL_VERTEX_SHADER;
    else if (path.ends_with(".frag")) stage = GL_FRAGMENT_SHADER;
    else if (path.ends_with(".comp")) stage = GL_COMPUTE_SHADER;
    else throw Error(path, "", "unknown shader stage (use .vert, .frag or .comp)");
    std::ostringstream src;
    src << "#version 450 core\n";
    for (const auto& d : defines) src << "#define " << d << "\n";
    std::vector<std::string> stack;
    expand_includes("shaders/gl/prelude.glsl", stack, src);
    expand_includes(path, stack, src);
    const std::string text = src.str();
    const char* ptr = text.c_str();
    const GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &ptr, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
        std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
        glGetShaderInfoLog(shader, len, nullptr, log.data());
        glDeleteShader(shader);
        throw Error(path, "compile", log);
    }
    return shader;
}

}  // namespace

namespace {
std::atomic<double> compile_seconds{0.0};
}

double program_compile_seconds() { return compile_seconds.load(); }

Program::Program(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
    struct Count {  // counts the time spent here, also when compiling or linking throws
        std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
        ~Count() { compile_seconds.fetch_add(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()); }
    } count;
    const GLuint program = glCreateProgram();
    handle_ = ProgramHandle(program);
    std::vector<GLuint> shaders;
    try {
        for (const auto& f : files) shaders.push_back(compile(f, defines));
    } catch (...) {
        for (GLuint s : shaders) glDeleteShader(s);
        throw;
    }
    for (GLuint s : shaders) glAttachShader(program, s);
    glLinkProgram(program);
    for (GLuint s : shaders) glDeleteShader(s);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
        std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
        glGetProgramInfoLog(program, len, nullptr, log.data());
        throw Error(files.empty() ? std::string() : files.front(), "link", log);
    }
}

RenderTarget::RenderTarget(int width, int height, GLenum color_format, int samples)
    : width_(width), height_(height), samples_(samples), format_(color_format) {
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_side);
    if (width <= 0 || height <= 0 || width > max_side || height > max_side)
        throw Error::parameter("render target", "size " + std::to_string(width) + "x" + std::to_string(height) +
                                                    " is outside 1.." + std::to_string(max_side) + " of this GPU");
    GLuint id = 0;
    glCreateRenderbuffers(1, &id);
    color_ = Renderbuffer(id);
    glNamedRenderbufferStorageMultisample(id, samples > 1 ? samples : 0, color_format, width, height);
    glCreateRenderbuffers(1, &id);
    depth_ = Renderbuffer(id);
    glNamedRenderbufferStorageMultisample(id, samples > 1 ? samples : 0, GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &id);
    fbo_ = Framebuffer(id);
    glNamedFramebufferRenderbuffer(id, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_.id());
    glNamedFramebufferRenderbuffer(id, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
    if (glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error::parameter("render target", "framebuffer is incomplete");
    if (samples > 1) {
        resolve_color_ = make_texture_2d(color_format, width, height);
        glCreateFramebuffers(1, &id);
        resolve_fbo_ = Framebuffer(id);
        glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, resolve_color_.id(), 0);
    }
    check_errors("RenderTarget");
}

void RenderTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width_, height_);
}

GLuint RenderTarget::resolve() const {
    if (samples_ <= 1) return fbo_.id();
    glBlitNamedFramebuffer(fbo_.id(), resolve_fbo_.id(), 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    return resolve_fbo_.id();
}

Image RenderTarget::read_back() const {
    const GLuint source = resolve();
    Image image(width_, height_, 4);
    std::vector<float> rows(image.pixels.size());
    glNamedFramebufferReadBuffer(source, GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, source);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, rows.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    check_errors("RenderTarget::read_back");
    const size_t row = static_cast<size_t>(width_) * 4;
    for (int y = 0; y < height_; ++y)  // GL's row 0 is the bottom; coif::Image's is the top
        std::copy_n(rows.data() + static_cast<size_t>(height_ - 1 - y) * row, row, image.pixels.data() + y * row);
    return image;
}

}  // namespace coif::gl
