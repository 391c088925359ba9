#include "online/body_pass.h"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "models/core/error.h"
#include "online/lighting_uniforms.h"

namespace coif::gl {
namespace {
struct BodyVertex {
    glm::vec3 position, normal;
};
std::vector<BodyVertex> body_vertices(const BodyMesh& mesh, const glm::mat3& orientation) {
    std::vector<BodyVertex> v(mesh.positions.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = {orientation * mesh.positions[i], glm::normalize(orientation * mesh.normals[i])};
    return v;
}
}  // namespace

void BodyPass::update(const BodyMesh& mesh, const glm::mat3& orientation) {
    if (mesh.positions.size() != vertex_count_ || mesh.triangles.size() * 3 != static_cast<std::size_t>(index_count_))
        throw Error::parameter("body", "a new pose must keep the mesh's vertex and triangle counts");
    const std::vector<BodyVertex> v = body_vertices(mesh, orientation);
    glNamedBufferSubData(vertices_.id(), 0, static_cast<GLsizeiptr>(v.size() * sizeof(BodyVertex)), v.data());
}

BodyPass::BodyPass(const BodyMesh& mesh, const glm::mat3& orientation) {
    if (mesh.positions.empty() || mesh.triangles.empty()) throw Error::parameter("body", "the mesh has no triangles");
    const std::vector<BodyVertex> v = body_vertices(mesh, orientation);
    vertex_count_ = v.size();
    vertices_ = make_buffer(v.data(), v.size() * sizeof(BodyVertex), GL_DYNAMIC_STORAGE_BIT);  // update(): new poses
    indices_ = make_buffer(mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
    index_count_ = static_cast<GLsizei>(mesh.triangles.size() * 3);
    vao_ = make_vertex_array();
    glVertexArrayVertexBuffer(vao_.id(), 0, vertices_.id(), 0, sizeof(BodyVertex));
    glVertexArrayElementBuffer(vao_.id(), indices_.id());
    float_attribute(vao_.id(), 0, 3, offsetof(BodyVertex, position), 0);
    float_attribute(vao_.id(), 1, 3, offsetof(BodyVertex, normal), 0);
    check_errors("BodyPass");
}

std::uint32_t BodyPass::draw(const FrameView& view, glm::vec2 jitter, int width, int height, std::span<const SrbfLight> lights) {
    if (lights_.id() == 0 || !std::equal(lights.begin(), lights.end(), lights_held_.begin(), lights_held_.end())) {
        lights_held_.assign(lights.begin(), lights.end());
        lights_ = make_lights_buffer(lights);
    }
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    if (width != width_ || height != height_) {
        color_ = make_texture_2d(GL_RGBA16F, width, height, Sampling{GL_NEAREST, GL_CLAMP_TO_EDGE});
        depth_ = make_texture_2d(GL_DEPTH_COMPONENT32F, width, height, Sampling{GL_NEAREST, GL_CLAMP_TO_EDGE});
        GLuint id = 0;
        glCreateFramebuffers(1, &id);
        fbo_ = Framebuffer(id);
        glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, color_.id(), 0);
        glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth_.id(), 0);
        if (glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error::parameter("body", "its framebuffer is incomplete");
        width_ = width, height_ = height;
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width, height);
    const float clear_color[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // no body: nothing to blend
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, clear_color);
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    program_.use();
    const glm::mat4 vp = pixel_shift(jitter, width, height) * view.projection * view.view;  // as the shells are shifted
    glUniformMatrix4fv(program_.uniform("u_view_projection"), 1, GL_FALSE, &vp[0][0]);
    glUniform3fv(program_.uniform("u_albedo"), 1, &kBodyAlbedo.x);
    glUniform3fv(program_.uniform("u_eye"), 1, &view.eye.x);
    glUniform1i(program_.uniform("u_light_count"), static_cast<GLint>(lights.size()));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, lights_.id());
    glBindVertexArray(vao_.id());
    glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    // The body over the frame (premultiplied "over": opaque where the body is, nothing elsewhere), every sample of a
    // multisampled frame.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(target));
    copy_.use();
    glBindTextureUnit(0, color_.id());
    glUniform1i(copy_.uniform("u_image"), 0);
    glUniform2i(copy_.uniform("u_origin"), 0, 0);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(vao_.id());  // core profile: some vertex array (fullscreen.vert reads none)
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    check_errors("BodyPass::draw");
    return depth_.id();
}

}  // namespace coif::gl
