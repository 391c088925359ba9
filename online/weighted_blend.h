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
//
// The k-buffer compositing (`kbuffer`, with k slots per pixel) keeps each pixel's k nearest fragments exact in front of
// that tail, in two passes over the shells (TressFX's "ShortCut" k-buffer):
//   1. shell_kbuffer_depth.frag: the k nearest eye distances per pixel, in increasing order (an atomic-minimum cascade
//      into `slot depth`, r32ui × k layers; no shading);
//   2. shell_kbuffer.frag: each fragment shaded; one whose distance a slot holds writes its premultiplied colour there
//      (`slot colour`, RGBA16F × k layers), every other one adds into the weighted tail as above;
// and the resolve composites the slots front to back, then the tail behind them. Memory: 20 + 12 k bytes per pixel.
// Nothing is dropped; what is approximate is the order of the fragments behind the k-th.
#include <glm/glm.hpp>
#include <map>
#include <memory>

#include "online/gl.h"

namespace coif::gl {

class WeightedBlend {
public:
    WeightedBlend();
    // Clears the targets for a width × height frame and binds them (begin), or binds them again without clearing (bind:
    // for a frame drawn in several draws with other passes between), with their blending. Draw with shell_weighted.frag.
    // `slots` > 0: the k-buffer's slots too, cleared to empty (their images bound by bind_slots).
    void begin(int width, int height, int slots = 0);
    void bind() const;
    // Binds the k-buffer's slot depths (image unit 1) and colours (unit 2), for its passes.
    void bind_slots() const;
    // Writes the composite into the bound draw framebuffer's viewport (whose origin in the framebuffer is `origin`): over
    // `background`, opaque; with `over`, premultiplied with alpha = 1 − Π, blended (ONE, ONE_MINUS_SRC_ALPHA, with
    // GL_FRAMEBUFFER_SRGB on) over what the framebuffer holds. Blending and GL_FRAMEBUFFER_SRGB are off afterwards.
    // With the slots of the last begin(), the k-buffer's resolve: the slots in front of the tail.
    void resolve(const glm::vec3& background, bool over = false, glm::ivec2 origin = glm::ivec2(0));

private:
    int width_ = 0, height_ = 0;
    int slots_ = 0, slot_width_ = 0, slot_height_ = 0, slot_layers_ = 0;  // this frame's slots; their textures' size
    Texture accum_, revealage_;
    Texture slot_depth_, slot_color_;  // r32ui, RGBA16F; layers ≥ slots_ (made on first use, grown)
    Framebuffer framebuffer_;
    Program resolve_;
    std::map<int, std::unique_ptr<Program>> slot_resolves_;  // the k-buffer's resolve, by its slots
    VertexArray empty_vao_;
};

}  // namespace coif::gl
