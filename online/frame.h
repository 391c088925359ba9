#pragma once
// How the shell renderer sees and where it draws one frame (online/shell_renderer.h draw_frame; the host-facing form
// is online/hair_renderer.h). GL-free: GL names cross as plain integers.
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "models/core/camera.h"

namespace coif::gl {

// A view: the view and projection matrices and the eye, in the space the shells are drawn in (for an instance of the
// hair, its own: the host's view times the instance's transform). Any projection (off-centre, jittered, reversed Z).
struct FrameView {
    glm::mat4 view{1.0f}, projection{1.0f};
    glm::vec3 eye{0.0f};

    static FrameView of(const Camera& camera) { return {camera.view(), camera.projection(), camera.eye}; }
    // The eye is where the view matrix puts the origin of eye space.
    static FrameView of(const glm::mat4& view, const glm::mat4& projection) {
        return {view, projection, glm::vec3(glm::inverse(view)[3])};
    }
};

// A sub-pixel shift of a width × height image by `jitter` pixels (x right, y down), as the clip-space translation put
// before a projection: render()'s supersampled frames, the viewer's refinement, and the body drawn under them.
inline glm::mat4 pixel_shift(glm::vec2 jitter, int width, int height) {
    return glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * jitter.x / width, -2.0f * jitter.y / height, 0.0f));
}

// Which convention the host's depth buffer follows (online/shells' shader variant SHELL_SCENE_DEPTH).
enum class DepthTest : int {
    none = 0,           // no scene depth: the hair is drawn whatever lies in front of it
    less_equal = 1,     // standard: smaller is nearer, cleared to 1 (glDepthFunc GL_LESS / GL_LEQUAL)
    greater_equal = 2,  // reversed Z: larger is nearer, cleared to 0 (glDepthFunc GL_GREATER / GL_GEQUAL)
};

// Where a frame goes: the framebuffer bound for drawing when the frame starts, within `viewport`.
struct FrameTarget {
    glm::ivec4 viewport{0, 0, 1, 1};  // x, y, width, height in pixels (GL's, y up)
    // Blend the hair premultiplied "over" what the framebuffer holds (alpha = coverage), clearing nothing; false:
    // replace the viewport's pixels with the hair over ShellSettings::background (coif render's images). This is the
    // exact compositing's choice; the blended modes (sorted, unsorted) always blend over what is there, instance by
    // instance.
    bool over = false;
    std::uint32_t scene_depth = 0;  // GL name of a 2D depth texture of the host's scene (texel = framebuffer pixel), or 0
    DepthTest depth_test = DepthTest::none;
};

}  // namespace coif::gl
