#include "online/hair_renderer.h"

#include <algorithm>
#include <cmath>

#include "online/gl.h"
#include "online/shell_renderer.h"

namespace coif {
namespace {

// The GL state draw() changes and puts back (online/hair_renderer.h lists it).
class SavedState {
public:
    SavedState() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb_);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fb_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
        blend_ = glIsEnabled(GL_BLEND);
        glGetIntegerv(GL_BLEND_SRC_RGB, &blend_func_[0]);
        glGetIntegerv(GL_BLEND_DST_RGB, &blend_func_[1]);
        glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_func_[2]);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_func_[3]);
        glGetIntegerv(GL_BLEND_EQUATION_RGB, &blend_eq_[0]);
        glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &blend_eq_[1]);
        depth_test_ = glIsEnabled(GL_DEPTH_TEST);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
        cull_ = glIsEnabled(GL_CULL_FACE);
        glGetIntegerv(GL_CULL_FACE_MODE, &cull_face_);
        glGetIntegerv(GL_FRONT_FACE, &front_face_);
        scissor_ = glIsEnabled(GL_SCISSOR_TEST);
        glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_);
        srgb_ = glIsEnabled(GL_FRAMEBUFFER_SRGB);
        discard_ = glIsEnabled(GL_RASTERIZER_DISCARD);
    }
    ~SavedState() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_fb_));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_fb_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
        glUseProgram(static_cast<GLuint>(program_));
        glBindVertexArray(static_cast<GLuint>(vao_));
        set(GL_BLEND, blend_);
        glBlendFuncSeparate(static_cast<GLenum>(blend_func_[0]), static_cast<GLenum>(blend_func_[1]),
                            static_cast<GLenum>(blend_func_[2]), static_cast<GLenum>(blend_func_[3]));
        glBlendEquationSeparate(static_cast<GLenum>(blend_eq_[0]), static_cast<GLenum>(blend_eq_[1]));
        set(GL_DEPTH_TEST, depth_test_);
        glDepthMask(depth_mask_);
        set(GL_CULL_FACE, cull_);
        glCullFace(static_cast<GLenum>(cull_face_));
        glFrontFace(static_cast<GLenum>(front_face_));
        set(GL_SCISSOR_TEST, scissor_);
        glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
        set(GL_FRAMEBUFFER_SRGB, srgb_);
        set(GL_RASTERIZER_DISCARD, discard_);
    }
    SavedState(const SavedState&) = delete;
    SavedState& operator=(const SavedState&) = delete;

private:
    static void set(GLenum cap, GLboolean on) { on ? glEnable(cap) : glDisable(cap); }
    GLint draw_fb_ = 0, read_fb_ = 0, viewport_[4] = {}, program_ = 0, vao_ = 0, blend_func_[4] = {}, blend_eq_[2] = {};
    GLint cull_face_ = 0, front_face_ = 0;
    GLboolean blend_ = 0, depth_test_ = 0, depth_mask_ = 0, cull_ = 0, scissor_ = 0, color_mask_[4] = {}, srgb_ = 0, discard_ = 0;
};

}  // namespace

HairRenderer::HairRenderer(const std::filesystem::path& asset) : HairRenderer(read_hair_asset(asset)) {}

HairRenderer::HairRenderer(CookedShells cooked)
    : defaults_(cooked.defaults), skinning_(cooked.skinning), roots_(cooked.roots), body_orientation_(cooked.body_orientation) {
    if (skinning_ && (skinning_->clusters.size() != cooked.shells.clusters() || roots_.size() != cooked.shells.clusters()))
        throw Error(cooked.source, "skinning", "one bone influence and root per cluster expected");
    renderer_ = std::make_unique<gl::ShellRenderer>(std::move(cooked));
}

const std::vector<std::string>& HairRenderer::bones() const {
    static const std::vector<std::string> none;
    return skinning_ ? skinning_->bones : none;
}

void HairRenderer::set_body(const BodyMesh* body) {
    if (!body) body_.reset();
    else body_ = body->turned(body_orientation_);
    const SavedState saved;  // the body's buffers and programs are made here
    apply_pose(std::vector<glm::mat4>(pose_));
}

void HairRenderer::apply_pose(std::span<const glm::mat4> bones) {
    std::vector<glm::mat4> m(bones.begin(), bones.end());
    if (m.empty() && skinning_) m.assign(skinning_->bones.size(), glm::mat4(1.0f));
    if (body_) {
        posed_ = *body_;
        if (skinning_ && !body_->bones.empty() && body_->influences.size() == body_->positions.size())
            skin_body(*body_, map_bone_matrices(m, skinning_->bones, body_->bones), posed_.positions, posed_.normals);
    }
    if (!skinning_) {  // the body alone, voxelized into the cooked grid
        renderer_->set_body(body_ ? &posed_ : nullptr, glm::mat3(1.0f), true);
        return;
    }
    renderer_->set_body(body_ ? &posed_ : nullptr, glm::mat3(1.0f), false);  // voxelized into the grid made next
    std::vector<glm::mat4> transforms(roots_.size());
    for (std::size_t c = 0; c < transforms.size(); ++c) transforms[c] = cluster_transform(skinning_->clusters[c], m, roots_[c]);
    renderer_->set_cluster_transforms(transforms);
    pose_.assign(bones.begin(), bones.end());
}

HairRenderer::~HairRenderer() = default;

glm::vec3 HairRenderer::bounds_min() const { return renderer_->bounds_min(); }
glm::vec3 HairRenderer::bounds_max() const { return renderer_->bounds_max(); }

void HairRenderer::draw(const FrameInputs& f) {
    if (f.viewport.z < 1 || f.viewport.w < 1) throw Error::parameter("frame viewport", "must have a positive width and height");
    if (f.depth_texture != 0 && f.depth_test == DepthTest::none)
        throw Error::parameter("frame depth_test", "a depth texture needs a convention (less_equal or greater_equal)");
    if (!f.bones.empty()) {
        if (!skinning_)
            throw Error::parameter("frame bones", "the asset has no bone weights (bake a style imported with --skinning)");
        if (f.bones.size() != skinning_->bones.size())
            throw Error::parameter("frame bones", std::to_string(f.bones.size()) + " matrices for the asset's " +
                                                      std::to_string(skinning_->bones.size()) + " bones");
        for (std::size_t b = 0; b < f.bones.size(); ++b)
            for (int col = 0; col < 4; ++col)
                for (int row = 0; row < 4; ++row)
                    if (!std::isfinite(f.bones[b][col][row]))
                        throw Error::parameter("frame bones " + std::to_string(b), "not finite");
    }
    const SavedState saved;
    if (!std::equal(f.bones.begin(), f.bones.end(), pose_.begin(), pose_.end())) apply_pose(f.bones);
    // The passes draw nothing the host's masks or tests would hide from them.
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_RASTERIZER_DISCARD);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, f.framebuffer);
    gl::FrameTarget target;
    target.viewport = f.viewport;
    target.over = true;
    target.scene_depth = f.depth_texture;
    target.depth_test = f.depth_test;  // unused without a depth texture (ShellsPass::draw)
    gl::ShellSettings s = f.settings ? *f.settings : defaults_;
    s.samples = 1;  // one frame per draw (the host antialiases, e.g. with its TAA and a jittered projection)
    s.timed = false;
    renderer_->draw_frame(f.view, f.projection, f.lights, s, target, f.instances);
}

}  // namespace coif
