#include "online/strand_preview.h"

#include <vector>

namespace coif::gl {

StrandPreview::StrandPreview(const Strands& strands)
    : program_({"shaders/gl/strand_preview.vert", "shaders/gl/strand_preview.frag"}) {
    struct Vertex {
        glm::vec3 position, tangent;
    };
    std::vector<Vertex> vertices(strands.points.size());
    std::vector<std::uint32_t> indices;
    indices.reserve(2 * strands.points.size());
    for (size_t s = 0; s < strands.strand_count(); ++s) {
        const std::uint32_t b = strands.offsets[s], e = strands.offsets[s + 1];
        for (std::uint32_t i = b; i < e; ++i) {
            const glm::vec3 prev = strands.points[i > b ? i - 1 : i], next = strands.points[i + 1 < e ? i + 1 : i];
            const glm::vec3 d = next - prev;
            vertices[i] = {strands.points[i], glm::length(d) > 0 ? glm::normalize(d) : glm::vec3(0, -1, 0)};
            if (i + 1 < e) {
                indices.push_back(i);
                indices.push_back(i + 1);
            }
        }
    }
    index_count_ = indices.size();
    vertices_ = make_buffer(vertices.data(), vertices.size() * sizeof(Vertex));
    indices_ = make_buffer(indices.data(), indices.size() * sizeof(std::uint32_t));
    vao_ = make_vertex_array();
    const GLuint vao = vao_.id();
    glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, indices_.id());
    float_attribute(vao, 0, 3, offsetof(Vertex, position), 0);
    float_attribute(vao, 1, 3, offsetof(Vertex, tangent), 0);
    check_errors("StrandPreview upload");
}

void StrandPreview::draw(const Camera& camera, const StrandPreviewSettings& settings) const {
    program_.use();
    const glm::mat4 view_projection = camera.projection() * camera.view();
    glUniformMatrix4fv(program_.uniform("u_view_projection"), 1, GL_FALSE, &view_projection[0][0]);
    const glm::vec3 light = glm::normalize(settings.light_direction);
    glUniform3fv(program_.uniform("u_light_direction"), 1, &light.x);
    glUniform3fv(program_.uniform("u_eye"), 1, &camera.eye.x);
    glUniform3fv(program_.uniform("u_hair_color"), 1, &settings.hair_color.x);
    glUniform1f(program_.uniform("u_specular_exponent"), settings.specular_exponent);
    glEnable(GL_DEPTH_TEST);
    glBindVertexArray(vao_.id());
    glDrawElements(GL_LINES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    check_errors("StrandPreview::draw");
}

Image render_strand_preview(const Strands& strands, const Camera& camera, const StrandPreviewSettings& settings) {
    RenderTarget target(camera.width, camera.height, GL_RGBA16F, settings.samples);
    target.bind();
    glClearColor(settings.background.x, settings.background.y, settings.background.z, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    StrandPreview preview(strands);
    preview.draw(camera, settings);
    return target.read_back();
}

}  // namespace coif::gl
