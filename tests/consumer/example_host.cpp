// An example host: a program that owns its GL context, its framebuffer, its own shaders and geometry, and draws the
// hair into its frame with coif's public API only (<coif/coif.h>). Its character is a head, an ellipsoid drawn with
// its own shader into its own HDR target and depth texture; the hair is drawn after it.
//   coif_example_host HAIR.coif [OUT.ppm]
// It checks what a host must be able to rely on, and exits 1 if any fails:
//   - where there is no hair, its frame is untouched, bit for bit (its clear colour and its head);
//   - the head hides the hair behind it (the hair's pixels there show the head, bit for bit);
//   - the hair in front of the head shows;
//   - the GL state it set is as it left it.
// Built in the tree (ctest online.ExampleHost) and, by tests/consumer/run.sh, against the installed package.
#include <coif/coif.h>
#if defined(__gl_h_) || defined(__GL_H__) || defined(EPOXY_GL_H) || defined(GL_VERSION_1_1)
#error "<coif/coif.h> must not include a GL header or loader"
#endif
#include <epoxy/gl.h>  // the host's own GL loader

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr float kClear[4] = {0.1f, 0.2f, 0.3f, 1.0f};

GLuint compile(GLenum stage, const char* text) {
    const GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        std::fprintf(stderr, "example host: shader: %s\n", log);
        std::exit(1);
    }
    return s;
}

struct Head {
    GLuint program = 0, vao = 0, buffer = 0;
    GLsizei count = 0;

    Head(glm::vec3 centre, glm::vec3 radii) {
        std::vector<float> v;  // position, normal
        const int rings = 32, segments = 48;
        const auto point = [&](int i, int j) {
            const float pi = std::numbers::pi_v<float>, th = pi * float(i) / rings, ph = 2.0f * pi * float(j) / segments;
            const glm::vec3 u(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
            const glm::vec3 p = centre + radii * u, n = glm::normalize(u / radii);
            v.insert(v.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
        };
        for (int i = 0; i < rings; ++i)
            for (int j = 0; j < segments; ++j) {
                point(i, j), point(i + 1, j), point(i + 1, j + 1);
                point(i, j), point(i + 1, j + 1), point(i, j + 1);
            }
        count = static_cast<GLsizei>(v.size() / 6);
        glCreateBuffers(1, &buffer);
        glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), 0);
        glCreateVertexArrays(1, &vao);
        glVertexArrayVertexBuffer(vao, 0, buffer, 0, 6 * sizeof(float));
        for (GLuint a = 0; a < 2; ++a) {
            glEnableVertexArrayAttrib(vao, a);
            glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
            glVertexArrayAttribBinding(vao, a, 0);
        }
        program = glCreateProgram();
        glAttachShader(program, compile(GL_VERTEX_SHADER, R"(#version 450 core
            layout(location = 0) in vec3 a_position;
            layout(location = 1) in vec3 a_normal;
            uniform mat4 u_view_projection;
            out vec3 v_normal;
            void main() { v_normal = a_normal; gl_Position = u_view_projection * vec4(a_position, 1.0); })"));
        glAttachShader(program, compile(GL_FRAGMENT_SHADER, R"(#version 450 core
            in vec3 v_normal;
            out vec4 o_color;
            void main() {
                float lambert = max(dot(normalize(v_normal), normalize(vec3(0.3, 0.8, 0.5))), 0.0);
                o_color = vec4(vec3(0.8, 0.55, 0.45) * (0.25 + 0.75 * lambert), 1.0);
            })"));
        glLinkProgram(program);
    }
    void draw(const glm::mat4& vp) const {
        glUseProgram(program);
        glUniformMatrix4fv(glGetUniformLocation(program, "u_view_projection"), 1, GL_FALSE, &vp[0][0]);
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, count);
    }
};

std::vector<float> read(GLuint framebuffer) {
    std::vector<float> p(static_cast<std::size_t>(kWidth) * kHeight * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, p.data());
    return p;
}

bool same(const std::vector<float>& a, const std::vector<float>& b, std::size_t pixel) {
    for (int c = 0; c < 4; ++c)
        if (a[pixel * 4 + c] != b[pixel * 4 + c]) return false;
    return true;
}
bool is_clear(const std::vector<float>& a, std::size_t pixel) {
    for (int c = 0; c < 4; ++c)  // RGBA16F holds the clear colour rounded to half precision
        if (std::abs(a[pixel * 4 + c] - kClear[c]) > 1e-3f) return false;
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: coif_example_host HAIR.coif [OUT.ppm]\n");
        return 2;
    }
    int failures = 0;
    const auto check = [&](bool ok, const std::string& what) {
        std::printf("example host: %s: %s\n", ok ? "ok" : "FAILED", what.c_str());
        failures += !ok;
    };
    try {
        auto context = coif::gl::Context::headless();  // a host would have its window's context current here
        coif::HairRenderer hair(argv[1]);

        // The host's frame: an HDR colour texture and a depth texture.
        GLuint color = 0, depth = 0, fb = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &color);
        glTextureStorage2D(color, 1, GL_RGBA16F, kWidth, kHeight);
        glCreateTextures(GL_TEXTURE_2D, 1, &depth);
        glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
        glCreateFramebuffers(1, &fb);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, color, 0);
        glNamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, depth, 0);

        // The camera and the head, placed from the hair's box: the head fills the upper middle of the hair.
        const glm::vec3 lo = hair.bounds_min(), hi = hair.bounds_max(), c = 0.5f * (lo + hi), e = hi - lo;
        const glm::vec3 head_centre(c.x, hi.y - 0.3f * e.y, c.z);
        const glm::vec3 head_radii = glm::vec3(0.3f * e.x, 0.28f * e.y, 0.3f * e.z);
        const Head head(head_centre, head_radii);
        const float distance = 1.6f * glm::length(e);
        const glm::mat4 view = glm::lookAt(c + glm::vec3(0.0f, 0.1f * e.y, distance), c, glm::vec3(0, 1, 0));
        const glm::mat4 projection = glm::perspective(glm::radians(40.0f), float(kWidth) / kHeight, 0.1f, 10.0f * distance);
        coif::SrbfLight lights[2];
        lights[0].L = glm::vec3(20.0f);
        lights[0].omega = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
        lights[0].lambda = 0.5f;
        lights[1].L = glm::vec3(2.0f);
        lights[1].omega = glm::vec3(0.0f, 1.0f, 0.0f);
        lights[1].lambda = 2.0f;

        const auto frame = [&](bool with_head, bool with_hair) {
            glBindFramebuffer(GL_FRAMEBUFFER, fb);
            glViewport(0, 0, kWidth, kHeight);
            glClearColor(kClear[0], kClear[1], kClear[2], kClear[3]);
            glClearDepth(1.0);
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            if (with_head) head.draw(projection * view);
            if (with_hair) {
                coif::FrameInputs f;
                f.view = view;
                f.projection = projection;
                f.framebuffer = fb;
                f.viewport = glm::ivec4(0, 0, kWidth, kHeight);
                f.depth_texture = depth;
                f.depth_test = coif::DepthTest::less_equal;
                f.lights = lights;
                hair.draw(f);
            }
            return read(fb);
        };
        // The host's frame alone, with the head, with the hair, with both.
        const std::vector<float> empty = frame(false, false), A = frame(true, false), B = frame(false, true), C = frame(true, true);

        // The host's state after draw(): as it set it.
        GLint bound = 0, program = 0, vao = 0, viewport[4] = {};
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
        glGetIntegerv(GL_VIEWPORT, viewport);
        GLboolean depth_mask = GL_FALSE;
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
        check(static_cast<GLuint>(bound) == fb && static_cast<GLuint>(program) == head.program &&
                  static_cast<GLuint>(vao) == head.vao && viewport[2] == kWidth && glIsEnabled(GL_DEPTH_TEST) &&
                  depth_mask == GL_TRUE && !glIsEnabled(GL_BLEND),
              "the host's framebuffer, program, vertex array, viewport, depth test and blending are as it left them");

        std::size_t untouched = 0, no_hair = 0, hidden = 0, in_front = 0, behind_head = 0, clear_kept = 0, clear_px = 0;
        for (std::size_t p = 0; p < static_cast<std::size_t>(kWidth) * kHeight; ++p) {
            // Exact: the faintest hair (a fibre's edge) counts as hair.
            const bool hair_here = !same(B, empty, p), head_here = !same(A, empty, p);
            if (!hair_here) {
                ++no_hair;
                untouched += same(A, C, p);
                if (!head_here) ++clear_px, clear_kept += is_clear(C, p) && same(C, empty, p);
            } else if (head_here) {
                ++behind_head;
                if (same(A, C, p)) ++hidden;
                else ++in_front;
            }
        }
        std::printf("example host: %zu pixels without hair, %zu with hair over the head (%zu hidden by it, %zu in front)\n",
                    no_hair, behind_head, hidden, in_front);
        check(no_hair > 0 && untouched == no_hair, "every pixel without hair keeps the host's frame bit for bit (" +
                                                       std::to_string(untouched) + " of " + std::to_string(no_hair) + ")");
        check(clear_px > 0 && clear_kept == clear_px, "the host's clear colour survives where there is neither head nor hair");
        check(hidden > kWidth * kHeight / 100, "the head hides the hair behind it: those pixels show the head");
        check(in_front > kWidth * kHeight / 100, "the hair in front of the head shows over it");

        if (argc > 2) {
            std::ofstream out(argv[2], std::ios::binary);
            out << "P6\n" << kWidth << " " << kHeight << "\n255\n";
            for (int y = kHeight - 1; y >= 0; --y)
                for (int x = 0; x < kWidth; ++x)
                    for (int ch = 0; ch < 3; ++ch) {
                        const float v = C[(static_cast<std::size_t>(y) * kWidth + x) * 4 + ch];
                        out.put(static_cast<char>(std::lround(255.0f * std::pow(std::clamp(v, 0.0f, 1.0f), 1.0f / 2.2f))));
                    }
        }
    } catch (const coif::Error& e) {
        std::fprintf(stderr, "example host: %s\n", e.what());
        return 1;
    }
    return failures ? 1 : 0;
}
