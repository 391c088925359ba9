#include "online/fragment_lists.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <numeric>

#include "models/core/error.h"
#include "models/core/image_metrics.h"

namespace coif::gl {

namespace {

constexpr std::uint64_t kColorBytes = 2 * sizeof(std::uint32_t), kLinkBytes = 2 * sizeof(std::uint32_t);
// Storage grows to this much more than the overflowing frame needed, so that a slowly changing view
// does not overflow again on the next frame.
constexpr double kGrowthMargin = 1.25;

// a lies behind b: composited before it (farther; at equal distance the lower node index).
bool behind(float depth_a, std::uint32_t node_a, float depth_b, std::uint32_t node_b) {
    return depth_a > depth_b || (depth_a == depth_b && node_a < node_b);
}

}  // namespace

// ---- CPU side ------------------------------------------------------------------------------------

Image composite_exact(const FragmentCapture& capture, const glm::vec3& background) {
    Image out(capture.width, capture.height, 4, 1.0f);
    std::vector<std::uint32_t> order;
    const std::size_t pixels = static_cast<std::size_t>(capture.width) * capture.height;
    for (std::size_t p = 0; p < pixels; ++p) {
        order.resize(capture.count(p));
        std::iota(order.begin(), order.end(), capture.first[p]);
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            return behind(capture.depth[a], capture.node[a], capture.depth[b], capture.node[b]);
        });
        glm::dvec3 c(background);
        for (std::uint32_t f : order) {  // 004 eq. 14, back to front, premultiplied
            const glm::dvec4 src(capture.color[f]);
            c = glm::dvec3(src) + (1.0 - src.a) * c;
        }
        float* px = out.pixels.data() + p * 4;
        for (int ch = 0; ch < 3; ++ch) px[ch] = static_cast<float>(c[ch]);
    }
    return out;
}

FragmentDepthStats fragment_depth_stats(const FragmentCapture& capture) {
    FragmentDepthStats s;
    const std::size_t pixels = static_cast<std::size_t>(capture.width) * capture.height;
    for (std::size_t p = 0; p < pixels; ++p) {
        const std::size_t n = capture.count(p);
        s.fragments += n;
        s.max = std::max(s.max, n);
        if (n > 0) ++s.covered_pixels;
        if (n > static_cast<std::size_t>(kResolveFragments)) ++s.pixels_over_resolve_limit;
    }
    s.mean_all = pixels ? static_cast<double>(s.fragments) / static_cast<double>(pixels) : 0.0;
    s.mean_covered = s.covered_pixels ? static_cast<double>(s.fragments) / static_cast<double>(s.covered_pixels) : 0.0;
    return s;
}

CompositingError compositing_error(const Image& exact, const Image& test, const FragmentCapture& capture) {
    if (exact.width != test.width || exact.height != test.height || exact.width != capture.width ||
        exact.height != capture.height)
        throw Error::parameter("compositing error", "the images and the capture differ in size");
    HairMask hair, all;
    hair.width = all.width = exact.width;
    hair.height = all.height = exact.height;
    const std::size_t pixels = static_cast<std::size_t>(exact.width) * exact.height;
    hair.inside.resize(pixels);
    all.inside.assign(pixels, 1);
    all.count = pixels;
    std::vector<float> peaks;
    for (std::size_t p = 0; p < pixels; ++p) {
        hair.inside[p] = capture.count(p) > 0;
        if (!hair.inside[p]) continue;
        ++hair.count;
        const float* e = exact.pixels.data() + p * exact.channels;
        peaks.push_back(std::max({e[0], e[1], e[2]}));
    }
    CompositingError r;
    r.hair_pixels = hair.count;
    if (peaks.empty()) {
        r.psnr_hair_db = r.psnr_all_db = std::numeric_limits<double>::infinity();
        return r;
    }
    const std::size_t k = std::min(peaks.size() - 1, static_cast<std::size_t>(kLinearPeakPercentile * static_cast<double>(peaks.size())));
    std::nth_element(peaks.begin(), peaks.begin() + static_cast<std::ptrdiff_t>(k), peaks.end());
    r.peak = std::max(static_cast<double>(peaks[k]), 1e-12);
    const Planes a = linear_planes(exact), b = linear_planes(test);
    r.psnr_hair_db = psnr(a, b, hair, r.peak);
    r.psnr_all_db = psnr(a, b, all, r.peak);
    double sq = 0;
    for (std::size_t p = 0; p < pixels; ++p)
        for (int ch = 0; ch < 3; ++ch) {
            const double d = static_cast<double>(a.c[ch][p]) - b.c[ch][p];
            r.max_abs = std::max(r.max_abs, std::abs(d));
            if (hair.inside[p]) sq += d * d;
        }
    r.rms_hair = std::sqrt(sq / (3.0 * static_cast<double>(hair.count)));
    return r;
}

// ---- GPU side ------------------------------------------------------------------------------------

FragmentLists::FragmentLists()
    : resolve_({"shaders/gl/shell_abuffer_resolve.comp"}, {"kResolveFragments " + std::to_string(kResolveFragments)}),
      copy_({"shaders/gl/fullscreen.vert", "shaders/gl/copy_texture.frag"}) {
    GLint64 block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
    // Node indices are uint32 and kFragmentListEnd is reserved.
    max_capacity_ = std::min<std::uint64_t>(static_cast<std::uint64_t>(block) / std::max(kColorBytes, kLinkBytes), kFragmentListEnd - 1);
    stats_.max_capacity = max_capacity_;
    const std::uint32_t zero = 0;
    counter_ = make_buffer(&zero, sizeof zero, GL_DYNAMIC_STORAGE_BIT);
    over_limit_ = make_buffer(&zero, sizeof zero, GL_DYNAMIC_STORAGE_BIT);
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    framebuffer_ = Framebuffer(id);
    empty_vao_ = make_vertex_array();
    check_errors("FragmentLists");
}

void FragmentLists::limit_capacity(std::uint64_t nodes) {
    max_capacity_ = std::min(max_capacity_, std::max<std::uint64_t>(nodes, 1));
    stats_.max_capacity = max_capacity_;
    if (capacity_ > max_capacity_) {  // made smaller at the next begin()
        capacity_ = 0;
        stats_.capacity = 0;
    }
}

void FragmentLists::reserve(std::uint64_t nodes) {
    nodes = std::min(nodes, max_capacity_);
    if (nodes <= capacity_) return;
    colors_ = make_buffer(nullptr, nodes * kColorBytes);
    links_ = make_buffer(nullptr, nodes * kLinkBytes);
    capacity_ = nodes;
    stats_.capacity = capacity_;
}

void FragmentLists::begin(int width, int height) {
    if (width != width_ || height != height_) {
        heads_ = make_texture_2d(GL_R32UI, width, height);
        resolved_ = make_texture_2d(GL_RGBA32F, width, height);
        glNamedFramebufferParameteri(framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
        glNamedFramebufferParameteri(framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
        glNamedFramebufferParameteri(framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_SAMPLES, 0);
        width_ = width;
        height_ = height;
    }
    reserve(std::max<std::uint64_t>(wanted_, static_cast<std::uint64_t>(kInitialNodesPerPixel) * width * height));
    const std::uint32_t end = kFragmentListEnd, zero = 0;
    glClearTexImage(heads_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &end);
    glNamedBufferSubData(counter_.id(), 0, sizeof zero, &zero);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
    bind();
}

void FragmentLists::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width_, height_);
    glBindImageTexture(0, heads_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, counter_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, colors_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, links_.id());
}

void FragmentLists::finish() {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    std::uint32_t count = 0;
    glGetNamedBufferSubData(counter_.id(), 0, sizeof count, &count);
    stats_.fragments = count;
    stats_.dropped = count > capacity_ ? count - capacity_ : 0;
    if (stats_.dropped > 0) wanted_ = static_cast<std::uint64_t>(static_cast<double>(count) * kGrowthMargin);
    stats_.pixels_over_resolve_limit = 0;
    if (resolved_this_frame_) {
        std::uint32_t over = 0;
        glGetNamedBufferSubData(over_limit_.id(), 0, sizeof over, &over);
        stats_.pixels_over_resolve_limit = over;
        resolved_this_frame_ = false;
    }
    check_errors("FragmentLists::finish");
}

void FragmentLists::resolve(const glm::vec3& background, bool over, glm::ivec2 origin) {
    const std::uint32_t zero = 0;
    glNamedBufferSubData(over_limit_.id(), 0, sizeof zero, &zero);
    resolve_.use();
    glUniform1ui(resolve_.uniform("u_capacity"), static_cast<GLuint>(capacity_));
    glUniform3fv(resolve_.uniform("u_background"), 1, &background.x);
    glUniform1i(resolve_.uniform("u_over"), over ? 1 : 0);
    glBindImageTexture(0, heads_.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glBindImageTexture(1, resolved_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 1, over_limit_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, colors_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, links_.id());
    glDispatchCompute(static_cast<GLuint>((width_ + 7) / 8), static_cast<GLuint>((height_ + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    // Into the bound framebuffer (a blit cannot write a multisampled one).
    copy_.use();
    glBindTextureUnit(0, resolved_.id());
    glUniform1i(copy_.uniform("u_image"), 0);
    glUniform2i(copy_.uniform("u_origin"), origin.x, origin.y);
    draw_fullscreen_into_frame(empty_vao_, over);
    resolved_this_frame_ = true;
    check_errors("FragmentLists::resolve");
}

FragmentCapture FragmentLists::read_back() const {
    FragmentCapture c;
    c.width = width_;
    c.height = height_;
    c.dropped = stats_.dropped;
    const std::size_t pixels = static_cast<std::size_t>(width_) * height_;
    const std::uint64_t stored = std::min<std::uint64_t>(stats_.fragments, capacity_);
    std::vector<std::uint32_t> heads(pixels);
    std::vector<std::uint32_t> colors(stored * 2);
    std::vector<std::uint32_t> links(stored * 2);
    glGetTextureImage(heads_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(pixels * sizeof(std::uint32_t)),
                      heads.data());
    if (stored > 0) {
        glGetNamedBufferSubData(colors_.id(), 0, static_cast<GLsizeiptr>(stored * kColorBytes), colors.data());
        glGetNamedBufferSubData(links_.id(), 0, static_cast<GLsizeiptr>(stored * kLinkBytes), links.data());
    }
    check_errors("FragmentLists::read_back");
    c.first.reserve(pixels + 1);
    c.color.reserve(stored);
    c.depth.reserve(stored);
    c.node.reserve(stored);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {  // GL's row 0 is the bottom; the capture's is the top
            c.first.push_back(static_cast<std::uint32_t>(c.color.size()));
            std::uint32_t n = heads[static_cast<std::size_t>(height_ - 1 - y) * width_ + x];
            std::size_t guard = 0;
            while (n != kFragmentListEnd) {
                if (n >= stored || ++guard > stored)
                    throw Error::parameter("fragment lists", "a list points outside the stored nodes (corrupt capture)");
                c.color.emplace_back(glm::unpackHalf2x16(colors[2 * n]), glm::unpackHalf2x16(colors[2 * n + 1]));
                float d = 0;
                std::memcpy(&d, &links[2 * n], sizeof d);
                c.depth.push_back(d);
                c.node.push_back(n);
                n = links[2 * n + 1];
            }
        }
    c.first.push_back(static_cast<std::uint32_t>(c.color.size()));
    return c;
}

}  // namespace coif::gl
