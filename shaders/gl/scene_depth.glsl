// The host scene's depth (online/hair_renderer.h FrameInputs): a shell fragment behind the scene's surface at its
// pixel is discarded, so that a head or a body hides the hair behind it. A compile-time variant, as every switch of
// the shell shading (llvmpipe runs both sides of a branch):
//   SHELL_SCENE_DEPTH 0  no scene depth
//   SHELL_SCENE_DEPTH 1  the standard convention: smaller is nearer (glDepthFunc GL_LESS / GL_LEQUAL, cleared to 1)
//   SHELL_SCENE_DEPTH 2  reversed Z: larger is nearer (GL_GREATER / GL_GEQUAL, cleared to 0)
// The fragment's own depth is gl_FragCoord.z from the host's projection, depth range and clip control, so it is
// comparable with what the host's depth buffer holds. u_scene_depth_offset: the texel of the scene's depth under
// this draw's pixel (0, 0) (the viewport's origin when the shells are drawn into a frame of the viewport's size).
#ifndef COIF_SHADERS_GL_SCENE_DEPTH_GLSL
#define COIF_SHADERS_GL_SCENE_DEPTH_GLSL
#ifndef SHELL_SCENE_DEPTH
#define SHELL_SCENE_DEPTH 0
#endif
#if SHELL_SCENE_DEPTH != 0
uniform sampler2D u_scene_depth;
uniform ivec2 u_scene_depth_offset;
bool behind_scene() {
    float scene = texelFetch(u_scene_depth, ivec2(gl_FragCoord.xy) + u_scene_depth_offset, 0).r;
#if SHELL_SCENE_DEPTH == 1
    return gl_FragCoord.z > scene;
#else
    return gl_FragCoord.z < scene;
#endif
}
#else
bool behind_scene() { return false; }
#endif

#endif  // COIF_SHADERS_GL_SCENE_DEPTH_GLSL
