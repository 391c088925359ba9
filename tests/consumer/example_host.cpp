// An example host: a program that owns its GL context, its framebuffer, its own shaders and geometry, and draws the
// hair into its frame with coif's public API only (<coif/coif.h>). Its character is drawn with its own shader into its
// own HDR target and depth texture, and the hair after it:
//   coif_example_host HAIR.coif [OUT.ppm]
//       the head is an ellipsoid placed from the hair's box;
//   coif_example_host HAIR.coif --body BODY --animate SPEC [OUT.ppm]
//       the character is BODY (a .tfxmesh or .obj, e.g. the Ratboy's), skinned by the host on the CPU and posed through
//       SPEC's keyframes (`coif render --animate`'s JSON), and the hair (baked from a style imported with --skinning)
//       follows the same bones through FrameInputs::bones and is shadowed by the body (HairRenderer::set_body). The
//       frames are the rest pose and SPEC's frames at its keys; OUT.ppm holds them side by side.
// In every frame it checks what a host must be able to rely on, and exits 1 if any fails:
//   - where there is no hair, its frame is untouched, bit for bit (its clear colour and its character);
//   - the character hides the hair behind it (the hair's pixels there show the character, bit for bit);
//   - the hair in front of the character shows;
//   - the GL state it set is as it left it;
// and, posed, that the pose moved the hair (its pixels differ from the rest frame's).
// Built in the tree (ctest online.ExampleHost, online.ExampleHostRatboy) and, by tests/consumer/run.sh, against the
// installed package.
#include <coif/coif.h>
#if defined(__gl_h_) || defined(__GL_H__) || defined(EPOXY_GL_H) || defined(GL_VERSION_1_1)
#error "<coif/coif.h> must not include a GL header or loader"
#endif
#include <epoxy/gl.h>  // the host's own GL loader

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 200, kHeight = 150;
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

// The host's character: triangles with positions and normals (updated when it is posed), drawn Lambertian.
struct Character {
    GLuint program = 0, vao = 0, buffer = 0, indices = 0;
    GLsizei count = 0;
    std::size_t vertices = 0;

    Character(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
              const std::vector<glm::uvec3>& triangles) : vertices(positions.size()) {
        count = static_cast<GLsizei>(triangles.size() * 3);
        glCreateBuffers(1, &buffer);
        glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(vertices * 6 * sizeof(float)), nullptr, GL_DYNAMIC_STORAGE_BIT);
        update(positions, normals);
        glCreateBuffers(1, &indices);
        glNamedBufferStorage(indices, static_cast<GLsizeiptr>(triangles.size() * sizeof(glm::uvec3)), triangles.data(), 0);
        glCreateVertexArrays(1, &vao);
        glVertexArrayVertexBuffer(vao, 0, buffer, 0, 6 * sizeof(float));
        glVertexArrayElementBuffer(vao, indices);
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
    void update(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals) const {
        std::vector<float> v;
        v.reserve(vertices * 6);
        for (std::size_t i = 0; i < vertices; ++i)
            v.insert(v.end(), {positions[i].x, positions[i].y, positions[i].z, normals[i].x, normals[i].y, normals[i].z});
        glNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data());
    }
    void draw(const glm::mat4& vp) const {
        glUseProgram(program);
        glUniformMatrix4fv(glGetUniformLocation(program, "u_view_projection"), 1, GL_FALSE, &vp[0][0]);
        glBindVertexArray(vao);
        glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
    }
};

// An ellipsoid head, as a BodyMesh without bones.
coif::BodyMesh ellipsoid(glm::vec3 centre, glm::vec3 radii) {
    coif::BodyMesh m;
    const int rings = 32, segments = 48;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const float pi = std::numbers::pi_v<float>, th = pi * float(i) / rings, ph = 2.0f * pi * float(j) / segments;
            const glm::vec3 u(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
            m.positions.push_back(centre + radii * u);
            m.normals.push_back(glm::normalize(u / radii));
        }
    const auto at = [&](int i, int j) { return static_cast<unsigned>(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

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
    std::filesystem::path asset, out, body_file, spec_file;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if ((a == "--body" || a == "--animate") && i + 1 < argc) (a == "--body" ? body_file : spec_file) = argv[++i];
        else if (asset.empty()) asset = a;
        else if (out.empty()) out = a;
        else asset.clear(), i = argc;
    }
    if (asset.empty() || body_file.empty() != spec_file.empty()) {
        std::fprintf(stderr, "usage: coif_example_host HAIR.coif [--body BODY --animate SPEC.json] [OUT.ppm]\n");
        return 2;
    }
    int failures = 0;
    std::string pose_label = "rest";
    const auto check = [&](bool ok, const std::string& what) {
        std::printf("example host: %s: %s: %s\n", pose_label.c_str(), ok ? "ok" : "FAILED", what.c_str());
        failures += !ok;
    };
    try {
        auto context = coif::gl::Context::headless();  // a host would have its window's context current here
        coif::HairRenderer hair(asset);

        // The host's frame: an HDR colour texture and a depth texture.
        GLuint color = 0, depth = 0, fb = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &color);
        glTextureStorage2D(color, 1, GL_RGBA16F, kWidth, kHeight);
        glCreateTextures(GL_TEXTURE_2D, 1, &depth);
        glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
        glCreateFramebuffers(1, &fb);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, color, 0);
        glNamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, depth, 0);

        // The hair's box places the ellipsoid head and, without a body, the camera.
        const glm::vec3 lo = hair.bounds_min(), hi = hair.bounds_max(), c = 0.5f * (lo + hi), e = hi - lo;
        glm::mat4 view = glm::lookAt(c + glm::vec3(0.0f, 0.1f * e.y, 1.6f * glm::length(e)), c, glm::vec3(0, 1, 0));
        float far = 16.0f * glm::length(e);
        coif::SrbfLight lights[2];
        lights[0].L = glm::vec3(20.0f);
        lights[0].omega = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
        lights[0].lambda = 0.5f;
        lights[1].L = glm::vec3(2.0f);
        lights[1].omega = glm::vec3(0.0f, 1.0f, 0.0f);
        lights[1].lambda = 2.0f;

        // The character, in the hair's space: the body (turned as the hair was), or a head filling the upper middle of the
        // hair. Its poses: rest, then each keyframe of the animation that moves it.
        coif::BodyMesh body;
        struct Pose {
            std::string label;
            std::vector<glm::mat4> hair_bones;  // over hair.bones(); empty: rest
            std::vector<glm::vec3> positions, normals;
        };
        std::vector<Pose> poses;
        if (!body_file.empty()) {
            if (hair.bones().empty()) throw coif::Error(asset, "bones", "the hair is not skinned: bake a style imported with --skinning");
            const coif::BodyMesh in_file = coif::read_body(body_file);
            hair.set_body(&in_file);  // its shadows on the hair
            body = in_file.turned(hair.body_orientation());
            poses.push_back({"rest", {}, body.positions, body.normals});
            // The host's animation: here coif's keyframe format; an engine gives its own skinning matrices.
            const coif::AnimationSpec spec = coif::read_animation_spec(spec_file);
            // The camera frames what moves, from three quarters above: the body's vertices weighted most to the bones the
            // animation turns (the head), up to the top of the hair.
            glm::vec3 head_lo(1e30f), head_hi(-1e30f);
            for (std::size_t i = 0; i < body.positions.size() && !body.influences.empty(); ++i) {
                const glm::ivec4 b = body.influences[i].bone;
                const glm::vec4 w = body.influences[i].weight;
                const int main = b[w[1] > w[0] ? 1 : 0];
                if (std::find(spec.bones.begin(), spec.bones.end(), body.bones[static_cast<std::size_t>(main)]) == spec.bones.end()) continue;
                head_lo = glm::min(head_lo, body.positions[i]);
                head_hi = glm::max(head_hi, body.positions[i]);
            }
            if (head_lo.x > head_hi.x) throw coif::Error(spec_file, "bones", "no vertex of the body weighs the animated bones most");
            head_hi.y = std::max(head_hi.y, hi.y);
            const glm::vec3 centre = 0.5f * (head_lo + head_hi);
            const float size = glm::length(head_hi - head_lo);
            view = glm::lookAt(centre + 1.3f * size * glm::normalize(glm::vec3(0.7f, 0.35f, 0.6f)), centre, glm::vec3(0, 1, 0));
            far = 10.0f * size;
            const coif::BonePose rest = coif::rest_pose(body);
            for (const coif::AnimationKey& key : spec.keys) {
                const int frame = static_cast<int>(std::lround(key.frame));
                const std::vector<glm::mat4> m = coif::animation_pose(spec, body.bones, rest, frame).matrices();
                if (std::all_of(m.begin(), m.end(), [](const glm::mat4& b) { return b == glm::mat4(1.0f); })) continue;
                Pose p{"frame " + std::to_string(frame), coif::map_bone_matrices(m, body.bones, hair.bones()), {}, {}};
                coif::skin_body(body, m, p.positions, p.normals);  // the host skins its own mesh (an engine: on the GPU)
                poses.push_back(std::move(p));
            }
        } else {
            body = ellipsoid(glm::vec3(c.x, hi.y - 0.3f * e.y, c.z), glm::vec3(0.3f * e.x, 0.28f * e.y, 0.3f * e.z));
            poses.push_back({"rest", {}, body.positions, body.normals});
        }
        const Character character(body.positions, body.normals, body.triangles);
        const glm::mat4 projection = glm::perspective(glm::radians(40.0f), float(kWidth) / kHeight, far / 1000.0f, far);

        std::vector<std::vector<float>> pictures;
        std::vector<float> rest_hair;
        for (const Pose& pose : poses) {
            pose_label = pose.label;
            character.update(pose.positions, pose.normals);
            const auto frame = [&](bool with_character, bool with_hair, bool black = false) {
                glBindFramebuffer(GL_FRAMEBUFFER, fb);
                glViewport(0, 0, kWidth, kHeight);
                if (black)
                    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
                else
                    glClearColor(kClear[0], kClear[1], kClear[2], kClear[3]);
                glClearDepth(1.0);
                glEnable(GL_DEPTH_TEST);
                glDepthFunc(GL_LESS);
                glDepthMask(GL_TRUE);
                glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                if (with_character) character.draw(projection * view);
                if (with_hair) {
                    coif::FrameInputs f;
                    f.view = view;
                    f.projection = projection;
                    f.framebuffer = fb;
                    f.viewport = glm::ivec4(0, 0, kWidth, kHeight);
                    f.depth_texture = depth;
                    f.depth_test = coif::DepthTest::less_equal;
                    f.lights = lights;
                    f.bones = pose.hair_bones;
                    hair.draw(f);
                }
                return read(fb);
            };
            // The host's frame alone, with the character, with the hair, with both.
            const std::vector<float> empty = frame(false, false), A = frame(true, false), B = frame(false, true), C = frame(true, true);
            // The hair over black too: a fibre too faint to move the clear colour's half floats still adds its light
            // there (and one whose light is nil still hides part of the clear colour).
            const std::vector<float> black = frame(false, false, true), B_black = frame(false, true, true);

            // The host's state after draw(): as it set it.
            GLint bound = 0, program = 0, vao = 0, viewport[4] = {};
            glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
            glGetIntegerv(GL_CURRENT_PROGRAM, &program);
            glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
            glGetIntegerv(GL_VIEWPORT, viewport);
            GLboolean depth_mask = GL_FALSE;
            glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
            check(static_cast<GLuint>(bound) == fb && static_cast<GLuint>(program) == character.program &&
                      static_cast<GLuint>(vao) == character.vao && viewport[2] == kWidth && glIsEnabled(GL_DEPTH_TEST) &&
                      depth_mask == GL_TRUE && !glIsEnabled(GL_BLEND),
                  "the host's framebuffer, program, vertex array, viewport, depth test and blending are as it left them");

            std::size_t untouched = 0, no_hair = 0, hidden = 0, in_front = 0, behind = 0, clear_kept = 0, clear_px = 0;
            std::size_t hair_px = 0, moved = 0;
            for (std::size_t p = 0; p < static_cast<std::size_t>(kWidth) * kHeight; ++p) {
                // Exact: the faintest hair (a fibre's edge) counts as hair.
                const bool hair_here = !same(B, empty, p) || !same(B_black, black, p), character_here = !same(A, empty, p);
                if (!hair_here) {
                    ++no_hair;
                    untouched += same(A, C, p);
                    if (!character_here) ++clear_px, clear_kept += is_clear(C, p) && same(C, empty, p);
                } else if (character_here) {
                    ++behind;
                    if (same(A, C, p)) ++hidden;
                    else ++in_front;
                }
                if (!rest_hair.empty()) {
                    const bool was_hair = !same(rest_hair, empty, p);
                    hair_px += hair_here || was_hair;
                    moved += (hair_here || was_hair) && !same(B, rest_hair, p);
                }
            }
            std::printf("example host: %s: %zu pixels without hair, %zu with hair over the character (%zu hidden by it, %zu in front)\n",
                        pose_label.c_str(), no_hair, behind, hidden, in_front);
            check(no_hair > 0 && untouched == no_hair, "every pixel without hair keeps the host's frame bit for bit (" +
                                                           std::to_string(untouched) + " of " + std::to_string(no_hair) + ")");
            check(clear_px > 0 && clear_kept == clear_px, "the host's clear colour survives where there is neither character nor hair");
            // Each on at least 0.5 % of the frame (150 pixels): a wrong depth convention or a lost draw leaves none.
            check(hidden > kWidth * kHeight / 200, "the character hides the hair behind it: those pixels show the character");
            check(in_front > kWidth * kHeight / 200, "the hair in front of the character shows over it");
            if (rest_hair.empty()) rest_hair = B;
            else  // the pose reached the hair: a tenth of its pixels (at rest or posed) changed
                check(10 * moved > hair_px, "the pose moved the hair (" + std::to_string(moved) + " of " + std::to_string(hair_px) +
                                                " hair pixels changed)");
            pictures.push_back(C);
        }

        if (!out.empty()) {  // the frames side by side
            std::ofstream file(out, std::ios::binary);
            file << "P6\n" << kWidth * pictures.size() << " " << kHeight << "\n255\n";
            for (int y = kHeight - 1; y >= 0; --y)
                for (const std::vector<float>& C : pictures)
                    for (int x = 0; x < kWidth; ++x)
                        for (int ch = 0; ch < 3; ++ch) {
                            const float v = C[(static_cast<std::size_t>(y) * kWidth + x) * 4 + ch];
                            file.put(static_cast<char>(std::lround(255.0f * std::pow(std::clamp(v, 0.0f, 1.0f), 1.0f / 2.2f))));
                        }
        }
    } catch (const coif::Error& e) {
        std::fprintf(stderr, "example host: %s\n", e.what());
        return 1;
    }
    return failures ? 1 : 0;
}
