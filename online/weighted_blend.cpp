#include "online/weighted_blend.h"

#include "models/core/error.h"

namespace coif::gl {

WeightedBlend::WeightedBlend() : resolve_({"shaders/gl/fullscreen.vert", "shaders/gl/weighted_resolve.frag"}) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    framebuffer_ = Framebuffer(id);
    empty_vao_ = make_vertex_array();
    check_errors("WeightedBlend");
}

void WeightedBlend::begin(int width, int height, int slots) {
    if (width != width_ || height != height_) {
        accum_ = make_texture_2d(GL_RGBA32F, width, height);
        revealage_ = make_texture_2d(GL_R32F, width, height);
        glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, accum_.id(), 0);
        glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT1, revealage_.id(), 0);
        const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(framebuffer_.id(), 2, buffers);
        if (glCheckNamedFramebufferStatus(framebuffer_.id(), GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error::parameter("OpenGL", "the weighted blend's framebuffer (RGBA32F + R32F) is incomplete");
        width_ = width;
        height_ = height;
    }
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    glClearTexImage(accum_.id(), 0, GL_RGBA, GL_FLOAT, zero);
    glClearTexImage(revealage_.id(), 0, GL_RED, GL_FLOAT, &one);
    slots_ = slots;
    if (slots > 0) {
        if (width != slot_width_ || height != slot_height_ || slots > slot_layers_) {
            slot_depth_ = make_texture_2d_array(GL_R32UI, width, height, slots);
            slot_color_ = make_texture_2d_array(GL_RGBA16F, width, height, slots);
            slot_width_ = width;
            slot_height_ = height;
            slot_layers_ = slots;
        }
        const GLuint empty = 0xffffffffu;
        glClearTexImage(slot_depth_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
        glClearTexImage(slot_color_.id(), 0, GL_RGBA, GL_FLOAT, zero);
    }
    bind();
}

void WeightedBlend::bind_slots() const {
    glBindImageTexture(1, slot_depth_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(2, slot_color_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
}

void WeightedBlend::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width_, height_);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunci(0, GL_ONE, GL_ONE);
    glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
}

void WeightedBlend::resolve(const glm::vec3& background, bool over, glm::ivec2 origin) {
    const Program* program = &resolve_;
    if (slots_ > 0) {
        auto& slot = slot_resolves_[slots_];
        if (!slot)
            slot = std::make_unique<Program>(std::vector<std::string>{"shaders/gl/fullscreen.vert", "shaders/gl/weighted_resolve.frag"},
                                             std::vector<std::string>{"KBUFFER_SLOTS " + std::to_string(slots_)});
        program = slot.get();
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        bind_slots();
    }
    const Program& p = *program;
    p.use();
    glBindTextureUnit(0, accum_.id());
    glBindTextureUnit(1, revealage_.id());
    glUniform1i(p.uniform("u_accum"), 0);
    glUniform1i(p.uniform("u_revealage"), 1);
    glUniform2i(p.uniform("u_origin"), origin.x, origin.y);
    glUniform3fv(p.uniform("u_background"), 1, &background.x);
    glUniform1i(p.uniform("u_over"), over ? 1 : 0);
    draw_fullscreen_into_frame(empty_vao_, over);
    check_errors("WeightedBlend::resolve");
}

}  // namespace coif::gl
