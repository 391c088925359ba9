// Headless OpenGL 4.5 core through EGL (llvmpipe here): render into an FBO and read it back.
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/strands.h"
#include "online/gl.h"
#include "online/gl_context.h"

namespace coif {
namespace {

TEST(GlContext, HeadlessCoreContextIs45) {
    auto context = gl::Context::headless();
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_FALSE(context->renderer().empty());
    std::printf("GL_RENDERER %s via %s\n", context->renderer().c_str(), context->platform().c_str());
}

TEST(GlContext, BlendedFullScreenLayersReadBackExactly) {
    auto context = gl::Context::headless();
    gl::Program program({"shaders/gl/fullscreen.vert", "shaders/gl/constant.frag"});
    gl::RenderTarget target(64, 32, GL_RGBA16F, 1);
    gl::VertexArray vao = gl::make_vertex_array();
    target.bind();
    glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    program.use();
    glUniform4f(program.uniform("u_color"), 1.0f, 0.5f, 0.0f, 0.25f);
    glBindVertexArray(vao.id());
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const Image img = target.read_back();
    // Two "over" operations with alpha 0.25: c = s + (c0 - s)·0.75².
    const float k = 0.75f * 0.75f;
    const float expected[3] = {1.0f + (0.2f - 1.0f) * k, 0.5f + (0.4f - 0.5f) * k, 0.0f + 0.6f * k};
    // RGBA16F stores 11 significant bits: each blend rounds by ≤ 2^-11 relative, so 2e-3 absolute bounds two of them.
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(img.at(x, y)[c], expected[c], 2e-3f) << x << "," << y;
}

TEST(GlContext, RefusesAbsurdTargetSizes) {
    auto context = gl::Context::headless();
    EXPECT_THROW(gl::RenderTarget(0, 10), Error);
    EXPECT_THROW(gl::RenderTarget(100000, 100000), Error);
}

}  // namespace
}  // namespace coif
