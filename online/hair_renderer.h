#pragma once
// coif::HairRenderer: cooked hair drawn into a host's own frame, with the host's camera and depth. This header (with
// <coif/coif.h>, which includes it) is what a game or tool needs; it includes no GL header or loader, and GL objects
// cross it as plain integer names.
//
//   coif bake style.json -o hair.coif                      // once, offline (online/shells/hair_asset.h)
//   coif::HairRenderer hair("hair.coif");                  // at load, with your GL 4.5 core context current
//   coif::FrameInputs f;                                   // every frame, after your opaque geometry:
//   f.view = view; f.projection = projection;              //   your matrices, any projection (reversed Z, jittered, …)
//   f.framebuffer = hdr_fbo; f.viewport = {0, 0, w, h};    //   your target, composited over
//   f.depth_texture = scene_depth; f.depth_test = coif::DepthTest::less_equal;
//   f.lights = lights;                                     //   SRBF lights, world space (shaders/srbf_light.h)
//   f.instances = transforms;                              //   world-from-hair, one per character wearing it
//   f.bones = skinning_matrices;                           //   a skinned asset: the character's pose (below)
//   hair.draw(f);
//
// A character. An asset baked from a style with bone weights (`coif style import --skinning X.tfxbone`) follows its
// character's skeleton: FrameInputs::bones gives, per bone of bones() in its order, the bone's rest-to-posed transform in
// the hair's space (an engine's skinning matrices, posed · inverse bind; models/skinning.h's BonePose makes them from
// rotations about pivots). Each cluster moves as one rigid body by the blend of its bones' transforms, its root where
// linear blend skinning puts the skin under it (models/skinning.h); its shadow grid is voxelized again from the moved
// strands with the posed body, and its shadows and lighting follow. A frame whose pose equals the last one's redoes
// none of it. set_body gives the body, which you draw yourself, for the shadows it casts on the hair: it is posed by the
// same matrices, matched to its own bones by name. The placement of the whole character is `instances`.
//
// What draw() does to your frame. Within the viewport of `framebuffer` it blends the hair premultiplied "over" what
// is there: colour = hair + (1 − coverage) · yours; alpha likewise. It clears nothing and writes no depth. Pixels
// without hair keep their values exactly. Hair whose fragment lies behind your depth at that pixel is not drawn.
//   Target formats: a linear HDR target (RGBA16F, RGBA32F: the hair is written in linear radiance, the lights'
//   units) or an sRGB one (GL_SRGB8_ALPHA8: GL_FRAMEBUFFER_SRGB is on while the hair blends, so it blends
//   linearly and is stored encoded). Tone mapping is yours.
//   Depth convention: `depth_texture` is a 2D texture of your scene's window-space depth (gl_FragCoord.z, as your
//   depth buffer holds it, e.g. its depth attachment), whose texel (x, y) is framebuffer pixel (x, y). The hair's
//   depth comes from your projection and your glDepthRange / glClipControl, so the two compare. DepthTest says which
//   way is nearer: less_equal (standard; cleared to 1) or greater_equal (reversed Z; cleared to 0). Bind your depth
//   texture to no framebuffer that draw() writes: it only reads it.
//
// GL state. draw() saves and restores: the draw and read framebuffer bindings, the viewport, the current program,
// the vertex array binding, blending (enable, functions, equations), the depth test (enable) and depth mask, face
// culling (enable, face) and the front face, the scissor test, the colour mask, GL_FRAMEBUFFER_SRGB and
// GL_RASTERIZER_DISCARD. It leaves bound to its own objects, as most engines expect to rebind per draw: texture
// units 0 … 13, image units 0 and 1, shader-storage buffer bindings 0 … 7, atomic-counter buffer bindings 0 and 1.
//
// Errors: the constructor and draw() throw coif::Error (models/core/error.h) naming the file or the input at fault;
// a failed draw() has restored the GL state. Messages (a frame that dropped fragments, tables being rebuilt after a
// parameter change) go to coif::set_log_sink's sink (models/core/log.h; default stderr), never straight to stderr.
//
// Threading and lifetime. A HairRenderer's GL objects belong to the context current at its construction: construct,
// draw and destroy it on a thread where that context (or one sharing its objects) is current, and destroy it before
// the context. One renderer draws one asset as many times per frame as `instances` says. Renderers are independent;
// do not call one from two threads at once. The asset file is read once at construction and can then be deleted.
//
// Cost: each instance keeps its own lights turned into the hair's space; their shadows are recomputed only when the
// lights or the instance's rotation change (0.1–0.5 s on llvmpipe for the default style and 40 lights), and the
// lighting pass runs per instance per frame (docs/renderer.md). A new pose costs its skinning and a new shadow grid
// (the grid: 9 ms for the Ratboy's mohawk on 2 cores, `coif bench animate`), and reruns the shadows and the lighting.
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "models/core/error.h"
#include "models/core/log.h"
#include "models/character.h"
#include "models/skinning.h"
#include "online/frame.h"
#include "online/shells/hair_asset.h"
#include "online/shells/shell_settings.h"
#include "shaders/srbf_light.h"

namespace coif {

namespace gl {
class ShellRenderer;
}
using gl::DepthTest;

struct FrameInputs {
    glm::mat4 view{1.0f}, projection{1.0f};  // yours: world to eye, eye to clip
    std::uint32_t framebuffer = 0;           // GL name of the framebuffer to composite into (0: the default one)
    glm::ivec4 viewport{0, 0, 0, 0};         // x, y, width, height in that framebuffer, pixels (GL's, y up); required
    std::uint32_t depth_texture = 0;         // GL name of your scene's depth (see above), or 0: the hair is not hidden
    DepthTest depth_test = DepthTest::less_equal;
    std::span<const SrbfLight> lights;       // world space; may change every frame
    const gl::ShellSettings* settings = nullptr;  // this frame's hair parameters; null: the asset's baked defaults
    std::span<const glm::mat4> instances;    // world from hair (rotation, translation, uniform scale); empty: identity
    // The character's pose (see above): one matrix per bone of HairRenderer::bones(), in the hair's space; empty: at
    // rest. One pose for every instance (a crowd in different poses: one renderer per character).
    std::span<const glm::mat4> bones;
};

class HairRenderer {
public:
    // Reads and uploads a cooked asset; throws coif::Error (the file named) if it cannot be read, is truncated,
    // corrupt or of another version, or exceeds the GPU's limits. Needs a current GL 4.5 core context.
    explicit HairRenderer(const std::filesystem::path& asset);
    explicit HairRenderer(CookedShells cooked);
    ~HairRenderer();
    HairRenderer(const HairRenderer&) = delete;
    HairRenderer& operator=(const HairRenderer&) = delete;

    // Draws every instance into the frame (see above). Throws coif::Error::parameter for an empty viewport, a
    // transform that is not rotation, translation and uniform scale, bones for an asset without bone weights or of
    // another count than bones(), a bone matrix that is not finite, or invalid parameters.
    void draw(const FrameInputs& frame);

    // The skeleton the asset's clusters are weighted to, the bones FrameInputs::bones follows; empty: not skinned.
    const std::vector<std::string>& bones() const;
    // The character's body (models/character.h read_body: a .tfxmesh or an .obj), in the frame of the strand file the
    // hair was made from, for the shadows it casts on the hair; null: none. Turned by body_orientation() into the hair's
    // space, posed by FrameInputs::bones through its own bone names (a body without bone weights stays at rest) and
    // voxelized into the shadow grid. You draw it yourself, turned the same way. Keeps a copy; needs the GL context.
    void set_body(const BodyMesh* body);
    // The turn from the hair's strand file's frame into the hair's space (CookedShells::body_orientation).
    const glm::mat3& body_orientation() const { return body_orientation_; }

    const gl::ShellSettings& defaults() const { return defaults_; }  // the parameters the asset was baked with
    // The hair's box in its own space (the placed outer shells), e.g. to frame or cull it.
    glm::vec3 bounds_min() const;
    glm::vec3 bounds_max() const;
    // The underlying renderer (online/shell_renderer.h; its header includes the GL loader).
    gl::ShellRenderer& shells() { return *renderer_; }

private:
    void apply_pose(std::span<const glm::mat4> bones);  // the body and the clusters posed, the grid made again
    std::unique_ptr<gl::ShellRenderer> renderer_;
    gl::ShellSettings defaults_;
    std::optional<StyleSkinning> skinning_;
    std::vector<glm::vec3> roots_;       // per cluster, in the hair's space
    glm::mat3 body_orientation_{1.0f};
    std::optional<BodyMesh> body_;       // set_body's, in the hair's space, at rest
    BodyMesh posed_;
    std::vector<glm::mat4> pose_;        // the bones of the last pose applied (empty: rest)
};

}  // namespace coif
