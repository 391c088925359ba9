#pragma once
// Weighted blended order-independent transparency (McGuire and Bavoil 2013, "Weighted Blended Order-Independent
// Transparency", JCGT 2(2)): the bounded-memory compositing mode `weighted` (docs/renderer.md "Decision 4").
//
// Every shell fragment i, shaded as the other modes shade it (shaders/gl/shell_weighted.frag), adds into two targets
// of the viewport's size, in any order:
//   accum      RGBA32F  Σ c_i w_i, Σ α_i w_i   (c_i premultiplied; w_i = α_i · weight(z_i), ONE, ONE)
//   revealage  R32F     Π (1 − α_i)           (ZERO, ONE_MINUS_SRC_COLOR)
// and the resolve writes C = (Σ c_i w_i / Σ α_i w_i) (1 − Π) + background · Π. The transmittance Π is exact; the colour
// is a weighted mean in which nearer fragments weigh more (z_i: the eye distance normalised to the hair's depth range
// in the view). Memory: 20 bytes per pixel, whatever the depth complexity, and no fragment is ever dropped.
#include <glm/glm.hpp>

#include "online/gl.h"

namespace coif::gl {

class WeightedBlend {
public:
    WeightedBlend();
    // Clears the targets for a width × height frame and binds them (begin), or binds them again without clearing (bind:
    // for a frame drawn in several draws with other passes between), with their blending. Draw with shell_weighted.frag.
    void begin(int width, int height);
    void bind() const;
    // Writes the composite into the bound draw framebuffer's viewport (whose origin in the framebuffer is `origin`): over
    // `background`, opaque; with `over`, premultiplied with alpha = 1 − Π, blended (ONE, ONE_MINUS_SRC_ALPHA, with
    // GL_FRAMEBUFFER_SRGB on) over what the framebuffer holds. Blending and GL_FRAMEBUFFER_SRGB are off afterwards.
    void resolve(const glm::vec3& background, bool over = false, glm::ivec2 origin = glm::ivec2(0));

private:
    int width_ = 0, height_ = 0;
    Texture accum_, revealage_;
    Framebuffer framebuffer_;
    Program resolve_;
    VertexArray empty_vao_;
};

}  // namespace coif::gl
