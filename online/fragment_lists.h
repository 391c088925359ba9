#pragma once
// Per-pixel fragment lists (an A-buffer) for exact compositing (004 eq. 14; DESIGN.md decision 4,
// docs/renderer.md "Decision 4: compositing").
//
// On the GPU (shaders/gl/shell_abuffer.frag appends, shell_abuffer_resolve.comp resolves):
//   heads     r32ui texture, one texel per pixel: the last node appended there, kFragmentListEnd if none
//   counter   one atomic counter: fragments seen this frame (also those that did not fit)
//   colors    RGBA16F per node: the fragment's premultiplied colour at the precision of the RGBA16F target
//             the blended modes write (8 bytes: llvmpipe's 128 MiB storage blocks hold 16 M fragments,
//             a 1920 × 1080 view of the default style ~9 M)
//   links     2 × uint32 per node: the eye distance (float bits) and the next node of the same pixel
// Nodes beyond the capacity are counted, not stored, so an overflowing frame loses fragments but never
// writes out of bounds; the next begin() grows the storage to what the counter asked for (up to the
// GPU's largest shader storage block), so the frame after an overflow is complete.
//
// On the CPU: read_back() returns the lists per pixel, and composite_exact() is the reference every
// compositing mode of the shell renderer is measured against: per pixel, the fragments sorted by eye
// distance and blended "over" back to front onto the background in double precision.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "models/core/image.h"
#include "online/gl.h"

namespace coif::gl {

inline constexpr std::uint32_t kFragmentListEnd = 0xffffffffu;
// Fragments per pixel the GPU resolve sorts in its local array (the nearest ones; the rest, all behind
// them, are blended order-independently: exact transmittance, α-weighted mean colour). 32 covers the
// default scene's pixels but its deepest few hundred (docs/renderer.md), at 32 × 8 bytes per pixel
// of local memory.
inline constexpr int kResolveFragments = 64;
// Storage the first frame reserves, in nodes per pixel (it grows to what a frame needs).
inline constexpr int kInitialNodesPerPixel = 8;

// One frame's fragments read back to the CPU, pixel-major (row 0 at the top, like coif::Image).
struct FragmentCapture {
    int width = 0, height = 0;
    std::vector<std::uint32_t> first;  // width·height + 1 offsets: pixel p owns [first[p], first[p + 1])
    std::vector<glm::vec4> color;      // premultiplied RGBA (as stored: half floats)
    std::vector<float> depth;          // eye distance
    std::vector<std::uint32_t> node;   // node index on the GPU: the order of equal distances
    std::uint64_t dropped = 0;         // fragments the storage could not hold (missing from the lists)

    std::size_t count(std::size_t pixel) const { return first[pixel + 1] - first[pixel]; }
};

// Exact "over" compositing of every captured fragment (004 eq. 14): per pixel sorted farther first
// (equal distances: lower node index first, as the GPU resolve does), C ← c_i + (1 − α_i) C from
// C = background, in double precision; alpha 1 (the renderer's targets are cleared to opaque).
Image composite_exact(const FragmentCapture& capture, const glm::vec3& background);

// Fragments per pixel of a capture: mean over all pixels, over the pixels with any, and the maximum.
struct FragmentDepthStats {
    double mean_all = 0, mean_covered = 0;
    std::size_t max = 0, covered_pixels = 0, pixels_over_resolve_limit = 0;
    std::uint64_t fragments = 0;
};
FragmentDepthStats fragment_depth_stats(const FragmentCapture& capture);

// Error of an image against the exact composite, linear RGB. PSNR = 10 log10(peak² / MSE), peak = the
// 99th percentile of the reference's largest channel over the hair pixels (models/core/image_metrics.h's
// linear peak); hair = the pixels with at least one captured fragment; "all" = every pixel.
struct CompositingError {
    double psnr_hair_db = 0, psnr_all_db = 0;  // +∞ when identical
    double rms_hair = 0, max_abs = 0, peak = 0;
    std::size_t hair_pixels = 0;
};
CompositingError compositing_error(const Image& exact, const Image& test, const FragmentCapture& capture);

struct FragmentListStats {
    std::uint64_t fragments = 0;                  // appended by the last frame (stored or not)
    std::uint64_t dropped = 0;                    // of those, not stored (over the capacity)
    std::uint64_t pixels_over_resolve_limit = 0;  // pixels the GPU resolve blended partly out of order
    std::uint64_t capacity = 0;                   // nodes the storage holds
    std::uint64_t max_capacity = 0;               // nodes it can grow to (the GPU's storage-block limit)
};

class FragmentLists {
public:
    FragmentLists();
    // Clears the lists for a width × height frame and binds an attachment-less framebuffer of that size
    // (single sample: one fragment per pixel and primitive, at the pixel centre), the heads (image unit
    // 0), the counter (atomic binding 0) and the node buffers (storage bindings 6, 7). Draw with
    // shell_abuffer.frag after this, then resolve() if wanted, then finish().
    void begin(int width, int height);
    // Binds the lists' framebuffer, heads, counter and nodes again (as begin() does, without clearing): for a frame
    // drawn in several draws with other passes between them, which use the same units.
    void bind() const;
    // Composites the lists over `background` (a compute pass into an RGBA32F texture) and copies the
    // result into the bound draw framebuffer's viewport (whose origin in the framebuffer is `origin`). With `over`,
    // the lists are composited over nothing instead and blended premultiplied "over" what the framebuffer holds
    // (ONE, ONE_MINUS_SRC_ALPHA, with GL_FRAMEBUFFER_SRGB on, so an sRGB target blends linearly); blending and
    // GL_FRAMEBUFFER_SRGB are off afterwards.
    void resolve(const glm::vec3& background, bool over = false, glm::ivec2 origin = glm::ivec2(0));
    // Waits for the frame and reads its figures (stats()); an overflowing frame makes the next begin()
    // grow the storage to what the counter asked for.
    void finish();
    FragmentCapture read_back() const;
    const FragmentListStats& stats() const { return stats_; }
    // Holds the storage to at most `nodes` fragments (below the GPU's limit): for tests of what happens beyond it.
    void limit_capacity(std::uint64_t nodes);

private:
    void reserve(std::uint64_t nodes);

    int width_ = 0, height_ = 0;
    std::uint64_t capacity_ = 0, max_capacity_ = 0, wanted_ = 0;
    Texture heads_, resolved_;
    Buffer counter_, over_limit_, colors_, links_;
    Framebuffer framebuffer_;
    Program resolve_, copy_;
    VertexArray empty_vao_;
    FragmentListStats stats_;
    bool resolved_this_frame_ = false;
};

}  // namespace coif::gl
