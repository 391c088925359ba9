#pragma once
// A character's body (models/character.h BodyMesh) drawn opaque for the shell renderer (online/shell_renderer.h
// set_body): into its own colour and depth textures of the frame's size, then copied into the frame, so that the
// hair's passes test their fragments against the body's depth (the shaders' scene depth, online/frame.h) and
// composite over it. Material: shaders/gl/body.frag (Lambertian, kBodyAlbedo, lit by the SRBF lights).
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "models/character.h"
#include "online/frame.h"
#include "online/gl.h"
#include "shaders/srbf_light.h"

namespace coif::gl {

// A neutral skin-like grey-brown, linear RGB: the body is there to be seen behind the hair, not to be judged.
inline constexpr glm::vec3 kBodyAlbedo{0.42f, 0.33f, 0.28f};

class BodyPass {
public:
    // Uploads the mesh turned by `orientation` (the hair's: the body is in the same file frame as its strands).
    // Throws coif::Error::parameter for an empty mesh.
    BodyPass(const BodyMesh& mesh, const glm::mat3& orientation);
    // The same mesh moved (a new pose): its vertices re-uploaded. Throws coif::Error::parameter if the counts differ.
    void update(const BodyMesh& mesh, const glm::mat3& orientation);

    // Draws the body seen through `view` (its projection shifted by `jitter` pixels as the shells are) into width ×
    // height textures, lit by `lights` (world space), then blends it opaque over what the framebuffer bound for drawing
    // holds (at its origin; pixels without body keep their values). Returns the GL name of the depth texture
    // (window-space depth, the standard convention), valid until the next draw.
    std::uint32_t draw(const FrameView& view, glm::vec2 jitter, int width, int height, std::span<const SrbfLight> lights);

    std::size_t triangles() const { return static_cast<std::size_t>(index_count_) / 3; }
    std::size_t vertices() const { return vertex_count_; }

private:
    Buffer vertices_, indices_;
    VertexArray vao_;
    GLsizei index_count_ = 0;
    std::size_t vertex_count_ = 0;
    Program program_{{"shaders/gl/body.vert", "shaders/gl/body.frag"}};
    Program copy_{{"shaders/gl/fullscreen.vert", "shaders/gl/copy_texture.frag"}};
    Buffer lights_;  // the lights of the last draw, uploaded when they change
    std::vector<SrbfLight> lights_held_;
    Framebuffer fbo_;
    Texture color_, depth_;
    int width_ = 0, height_ = 0;
};

}  // namespace coif::gl
