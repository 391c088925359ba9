#include "online/strand_renderer.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "models/core/error.h"
#include "models/strands.h"

namespace coif::gl {

namespace {

constexpr int kFirstLutUnit = 0;

// std430 mirrors of the GLSL structs (shaders/gl/strand_lines.frag).
struct Vertex {
    glm::vec3 position, tangent;
};

}  // namespace

StrandRenderer::StrandRenderer(const Strands& strands)
    : lighting_({"shaders/gl/strand_lighting.comp"}), lines_({"shaders/gl/strand_lines.vert", "shaders/gl/strand_lines.frag"}) {
    // Two vertices per segment, both with the segment's direction as tangent (the reference's frame,
    // offline/reference.cpp), so segment k is vertices 2k, 2k + 1.
    std::vector<Vertex> vertices;
    vertices.reserve(2 * strands.points.size());
    for (std::size_t s = 0; s < strands.strand_count(); ++s) {
        const std::uint32_t first = strands.offsets[s], last = strands.offsets[s + 1] - 1;
        for (std::uint32_t p = first; p < last; ++p) {
            const glm::vec3 a = strands.points[p], b = strands.points[p + 1], d = b - a;
            // Zero-length segments (repeated points) borrow the strand's chord, as the reference does.
            const glm::vec3 chord = strands.points[last] - strands.points[first];
            const glm::vec3 t = glm::length(d) > 0 ? glm::normalize(d)
                              : glm::length(chord) > 0 ? glm::normalize(chord) : glm::vec3(0, -1, 0);
            vertices.push_back({a, t});
            vertices.push_back({b, t});
            midpoints_.push_back(0.5f * (a + b));
        }
    }
    if (midpoints_.empty()) throw Error::parameter("strands", "no segments to draw");
    auto_radius_ = coif::auto_fiber_radius(strands);
    order_.resize(midpoints_.size());
    index_scratch_.resize(2 * midpoints_.size());
    std::iota(index_scratch_.begin(), index_scratch_.end(), 0u);
    vertex_count_ = vertices.size();
    vertices_ = make_buffer(vertices.data(), vertices.size() * sizeof(Vertex));
    radiance_ = make_buffer(nullptr, std::max<std::size_t>(1, vertices.size()) * sizeof(glm::vec4));
    indices_ = make_buffer(index_scratch_.data(), index_scratch_.size() * sizeof(std::uint32_t), GL_DYNAMIC_STORAGE_BIT);
    vao_ = make_vertex_array();
    const GLuint vao = vao_.id();
    glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, indices_.id());
    float_attribute(vao, 0, 3, offsetof(Vertex, position), 0);
    float_attribute(vao, 1, 3, offsetof(Vertex, tangent), 0);
    glVertexArrayVertexBuffer(vao, 1, radiance_.id(), 0, sizeof(glm::vec4));
    float_attribute(vao, 2, 3, 0, 1);
    GLuint q[2];
    glCreateQueries(GL_TIME_ELAPSED, 2, q);
    query_lighting_ = Query(q[0]);
    query_lines_ = Query(q[1]);
    check_errors("StrandRenderer upload");
}

void StrandRenderer::set_lights(std::span<const SrbfLight> lights) {
    lights_ = make_lights_buffer(lights);
    light_count_ = static_cast<int>(lights.size());
}

float StrandRenderer::fiber_radius(const StrandSettings& s) const {
    if (!std::isfinite(s.fiber_radius) || s.fiber_radius < 0)
        throw Error::parameter("fibre radius", "must be a finite number >= 0 (0 = auto)");
    return s.fiber_radius > 0 ? s.fiber_radius : auto_radius_;
}

void StrandRenderer::draw(const Camera& camera, const StrandSettings& s) {
    const float radius = fiber_radius(s);
    shading::validate(s.hair, "strand renderer settings");
    tables_.update(s.hair.fibre, s.hair.config);
    glViewport(0, 0, camera.width, camera.height);
    if (s.alpha) glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    else glClearColor(s.background.x, s.background.y, s.background.z, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    if (s.sort_segments) {
        std::vector<float> dist(midpoints_.size());
        for (std::size_t k = 0; k < midpoints_.size(); ++k) dist[k] = glm::distance(camera.eye, midpoints_[k]);
        std::iota(order_.begin(), order_.end(), 0u);
        std::stable_sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) { return dist[a] > dist[b]; });
        for (std::size_t k = 0; k < order_.size(); ++k) {
            index_scratch_[2 * k] = 2 * order_[k];
            index_scratch_[2 * k + 1] = 2 * order_[k] + 1;
        }
    } else {
        std::iota(index_scratch_.begin(), index_scratch_.end(), 0u);
    }
    glNamedBufferSubData(indices_.id(), 0, static_cast<GLsizeiptr>(index_scratch_.size() * sizeof(std::uint32_t)),
                         index_scratch_.data());

    timings_ = {};
    if (!s.per_fragment) {  // the lighting pass: L_o per strand point
        glBeginQuery(GL_TIME_ELAPSED, query_lighting_.id());
        lighting_.use();
        set_shading_uniforms(lighting_, camera, s);
        glUniform1i(lighting_.uniform("u_vertex_count"), static_cast<GLint>(vertex_count_));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, vertices_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, radiance_.id());
        glDispatchCompute(static_cast<GLuint>((vertex_count_ + 63) / 64), 1, 1);
        glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
        glEndQuery(GL_TIME_ELAPSED);
    } else if (!lines_per_fragment_.id()) {
        lines_per_fragment_ = Program({"shaders/gl/strand_lines.vert", "shaders/gl/strand_lines.frag"}, {"COIF_STRAND_PER_FRAGMENT"});
    }

    glBeginQuery(GL_TIME_ELAPSED, query_lines_.id());
    const Program& lines = s.per_fragment ? lines_per_fragment_ : lines_;
    lines.use();
    if (s.per_fragment) set_shading_uniforms(lines, camera, s);
    const glm::mat4 view = camera.view(), view_projection = camera.projection() * view;
    glUniformMatrix4fv(lines.uniform("u_view_projection"), 1, GL_FALSE, &view_projection[0][0]);
    glUniformMatrix4fv(lines.uniform("u_view"), 1, GL_FALSE, &view[0][0]);
    // 2r/p with p = 2 z tan(fov/2) / height: alpha = min(1, u_coverage_scale / z).
    glUniform1f(lines.uniform("u_coverage_scale"), radius * static_cast<float>(camera.height) / std::tan(0.5f * camera.fov_y));

    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over"
    glBindVertexArray(vao_.id());
    glDrawElements(GL_LINES, static_cast<GLsizei>(index_scratch_.size()), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEndQuery(GL_TIME_ELAPSED);
    check_errors("StrandRenderer::draw");
    GLuint64 ns = 0;
    if (!s.per_fragment) {
        glGetQueryObjectui64v(query_lighting_.id(), GL_QUERY_RESULT, &ns);
        timings_.lighting_ms = static_cast<double>(ns) * 1e-6;
    }
    glGetQueryObjectui64v(query_lines_.id(), GL_QUERY_RESULT, &ns);
    timings_.lines_ms = static_cast<double>(ns) * 1e-6;
}

// The uniforms of shaders/gl/strand_lighting.glsl, for the program in use.
void StrandRenderer::set_shading_uniforms(const Program& program, const Camera& camera, const StrandSettings& s) {
    glUniform3fv(program.uniform("u_eye"), 1, &camera.eye.x);
    glUniform1i(program.uniform("u_light_count"), light_count_);
    glUniform1i(program.uniform("u_lobes"), s.hair.lobes);
    glUniform1i(program.uniform("u_multiple"), s.hair.multiple ? 1 : 0);
    set_lighting_uniforms(program, s.hair.fibre, s.hair.config);
    tables_.bind(program, kFirstLutUnit);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, lights_.id());  // shaders/gl/srbf_lights.glsl
}

Image StrandRenderer::render(const Camera& camera, const StrandSettings& settings) {
    RenderTarget target(camera.width, camera.height, GL_RGBA16F, settings.samples);
    target.bind();
    draw(camera, settings);
    Image image = target.read_back();
    if (settings.alpha && image.channels == 4)  // premultiplied → straight: RGB = C / A where something was drawn
        for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
            const float a = image.pixels[i + 3];
            for (int c = 0; c < 3; ++c) image.pixels[i + c] = a > 0.0f ? image.pixels[i + c] / a : 0.0f;
        }
    return image;
}

}  // namespace coif::gl
