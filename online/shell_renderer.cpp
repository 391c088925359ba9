#include "online/shell_renderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>

#include "models/core/error.h"
#include "models/core/log.h"
#include "models/core/statistics.h"
#include "models/core/units.h"
#include "online/body_pass.h"
#include "online/shell_passes.h"
#include "online/shells/record_atlas.h"
#include "online/shells/shadow_grid.h"
#include "shaders/lighting.h"

namespace coif::gl {
namespace {

using Clock = std::chrono::steady_clock;

// The largest entry of RᵀR − I: how far R is from a rotation's columns (orthogonal, of length 1).
float orthonormality_error(const glm::mat3& R) {
    const glm::mat3 E = glm::transpose(R) * R - glm::mat3(1.0f);
    float off = 0.0f;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) off = std::max(off, std::abs(E[c][r]));
    return off;
}
// Whether M's last row is (0, 0, 0, 1).
bool affine(const glm::mat4& M) { return M[0][3] == 0.0f && M[1][3] == 0.0f && M[2][3] == 0.0f && M[3][3] == 1.0f; }

// How far a skipped lighting sample's axis may lie from the interpolation between the lit ones (lighting_step_within):
// 4°, about half of 000's β_R of 7.5°, the narrowest lobe. The default style's 90th percentile is 2.4° at step 2 and 6.8°
// at step 4; Curly_100's fitted clusters are 5.6° at step 2 (docs/renderer.md, "Quality presets").
constexpr float kLightingStepMaxAngle = 4.0f * static_cast<float>(kPi) / 180.0f;
}  // namespace

// The shadow pass's inputs when it last ran (it reruns only when they or the lights change): the fibres' radius, the
// lighting step it marched at, where its rays start (ShellSettings::shadow_neighbours, shadow_outward) and whether it
// writes the own cluster's inner depths (own_cluster_inner).
struct ShadowKey {
    bool valid = false;
    float radius = -1.0f;
    int step = 0;
    bool narrow = false;
    float outward = 0.0f;
    bool inner = false;
    bool operator==(const ShadowKey&) const = default;
};

// The lights of one instance of the hair as its own space sees them, and what depends on them: their shadows and the
// lighting sums (draw_frame). Swapped into the ShellGpu while that instance is drawn.
struct InstanceLights {
    std::vector<SrbfLight> lights;  // turned into the hair's space
    Buffer buffer, shadows;
    int count = 0;
    Texture lighting;
    LightingKey lighting_key;  // what `lighting` holds the sums of
    std::uint64_t lights_stamp = 0;
    ShadowKey shadow_key;  // what `shadows` holds
    std::vector<int> levels;  // its clusters' levels of detail (ShellDraw::levels)
    std::vector<SrbfLight> values;  // what `buffer` holds (ShellGpu::light_values)
    KeyLightVolumes key_lights;     // its key lights' shadow volumes
};

struct ShellRenderer::Impl {
    ShadowPass shadow;
    KeyLightPass key_light;
    bool key_grid_made = false;  // gpu's key grid (ShellGpu::set_key_grid) is of the grid's strands as they are now
    double depth_pass_ms = 0;  // the k-buffer's depth passes of this frame so far (timed), added to its shells' time
    LightingPass lighting;
    ShellsPass shells_pass;
    PreparedShells shells;
    std::unique_ptr<ShellGpu> gpu;
    ShadowKey shadow_key;  // what gpu->shadows holds
    glm::vec2 jitter{0.0f};  // sub-pixel image shift of the next draw (render()'s supersampling), pixels
    ShellDraw::Detail detail = ShellDraw::Detail::follow;  // how the next draws pick levels of detail (render(): fresh, hold)
    // What gpu->lighting holds the sums of: a frame whose inputs are the same (render()'s shifted frames among them:
    // the jitter moves only the image) reuses them (ShellSettings::reuse_lighting).
    LightingKey lighting_key;
    std::vector<InstanceLights> instances;  // draw_frame's, by instance index
    bool in_render = false;  // render() draws again or in tiles what overflows: no warning then
    std::map<int, int> lighting_steps;      // ShellSettings::lighting_step → the step this style allows (lighting_step_within)
    std::unique_ptr<BodyPass> body;         // set_body's, drawn by draw_view
    std::vector<SrbfLight> lights;          // set_lights' (world space), which light the body in draw_view
    std::optional<BodyMesh> body_mesh;      // and its mesh, voxelized again into each new shadow grid
    glm::mat3 body_orientation{1.0f};
    DensityGrid grid;                       // the hair's own shadow grid (set_body extends a copy of it)
    std::vector<ShellInstance> cooked_instances;  // the placements as cooked, kept by the first set_cluster_transforms
    std::vector<LightingSample> cooked_samples;
    ShadowStrands shadow_source;  // the grid's strands as cooked
    // A copy of them, made when first needed (make_key_grid, set_cluster_transforms), as set_cluster_transforms last
    // moved them.
    Strands strands;
    Strands& strands_now() {
        if (strands.points.empty() && !shadow_source.points.empty()) strands = shadow_source.strands();
        return strands;
    }
    std::vector<std::uint32_t> shadow_strand_cluster;

    void invalidate_shadows() {
        shadow_key.valid = false;
        lighting_key.valid = false;
        for (InstanceLights& il : instances) il.shadow_key.valid = false, il.lighting_key.valid = false;
    }
    // The hair's grid, grown to hold the body beside it (extend_grid), and the body's voxels on it; uploaded. Returns
    // the uploaded grid's dimensions.
    glm::ivec3 upload_grid() {
        DensityGrid grown;
        if (body_mesh) {
            const auto [lo, hi] = body_mesh->bounds(body_orientation);
            grown = extend_grid(grid, lo, hi);
        }
        const DensityGrid& g = body_mesh ? grown : grid;
        gpu->set_grid(g);
        gpu->set_body(body_mesh ? voxelize_body(*body_mesh, body_orientation, g) : std::vector<std::uint8_t>{}, g.dims);
        invalidate_shadows();
        return g.dims;
    }

    int lighting_step(int wanted) {
        auto it = lighting_steps.find(wanted);
        if (it == lighting_steps.end()) {
            lit_rows(shells.lighting_rows, wanted);  // validates
            it = lighting_steps.emplace(wanted, lighting_step_within(shells, wanted, kLightingStepMaxAngle)).first;
        }
        return it->second;
    }

    void swap(InstanceLights& l) {
        std::swap(gpu->lights, l.buffer);
        std::swap(gpu->shadows, l.shadows);
        std::swap(gpu->light_count, l.count);
        std::swap(gpu->lighting, l.lighting);
        std::swap(lighting_key, l.lighting_key);
        std::swap(gpu->lights_stamp, l.lights_stamp);
        std::swap(shadow_key, l.shadow_key);
        std::swap(gpu->light_values, l.values);
        std::swap(gpu->key_lights, l.key_lights);
    }
    // The key lights' fine grid (ShellSettings::key_lights), made on first use after each change of the strands: the
    // grid's strands as they are now voxelized at kKeyLightGridSize, or the shadow grid itself where the renderer has no
    // strands (set_shadow_grid's).
    // Returns whether it made it now. With motion it is made again each frame the strands moved (docs/renderer.md,
    // "Key lights": its cost).
    bool make_key_grid() {
        if (key_grid_made) return false;
        const Strands& now = strands_now();
        gpu->set_key_grid(now.points.empty() ? grid : voxelize_strands(now, glm::mat3(1.0f), kKeyLightGridSize));
        key_grid_made = true;
        return true;
    }
};

namespace {

void validate(const ShellSettings& s) {
    if (!(s.tangent_spread <= 60.0f * float(kPi / 180.0))) throw Error::parameter("tangent_spread", "must be at most 60 degrees");
    if (s.neighbours < 1 || s.neighbours > kMaxShellNeighbours)
        throw Error::parameter("neighbours", "must be 1.." + std::to_string(kMaxShellNeighbours));
    if (s.fourier_order < 0 || s.fourier_order > 4) throw Error::parameter("fourier_order", "must be 0..4");
}

}  // namespace

ShellRenderer::ShellRenderer(CookedShells cooked) : impl_(std::make_unique<Impl>()) {
    const auto start = Clock::now();
    set_hair(std::move(cooked));
    stats_.prepare_seconds = std::chrono::duration<double>(Clock::now() - start).count();
}

void ShellRenderer::set_hair(CookedShells cooked) {
    Impl& m = *impl_;
    if (cooked.shells.clusters() == 0) throw Error(cooked.source, "clusters", "the hair has no clusters");
    const RecordAtlas& atlas = cooked.atlas;
    const auto upload = Clock::now();
    // Made before anything changes: a hair the GPU cannot hold leaves the last one drawn.
    auto gpu = std::make_unique<ShellGpu>(cooked.shells, atlas, cooked.grid, cooked.source);
    glFinish();  // the upload's copies done, so that upload_seconds holds them
    stats_.upload_seconds = std::chrono::duration<double>(Clock::now() - upload).count();
    m.gpu = std::move(gpu);
    m.shells = std::move(cooked.shells);
    // What was of the last hair: its motion, its instances' lights, its lighting steps.
    m.instances.clear();
    m.lighting_steps.clear();
    m.cooked_instances.clear();
    m.cooked_samples.clear();
    m.shadow_source = ShadowStrands{};
    m.strands = Strands{};
    m.shadow_strand_cluster.clear();
    m.key_grid_made = false;
    m.shells_pass.forget_shells();  // its cached boxes were of the last hair's meshes
    m.invalidate_shadows();

    const PreparedShells& p = m.shells;
    stats_.clusters = p.clusters();
    stats_.prototypes = p.prototypes.size();
    stats_.sectors = p.sectors.size();
    stats_.triangles = p.triangles;
    stats_.lighting_samples = p.samples.size();
    stats_.records = atlas.mean_alpha.size();
    stats_.database_records = cooked.database_records;
    stats_.atlas_width = atlas.width;
    stats_.atlas_height = atlas.height;
    stats_.re_norm = atlas.re_norm;
    stats_.shadow_strands = cooked.shadow_strands;
    m.grid = std::move(cooked.grid);  // kept: set_body grows a copy of it
    if (cooked.shadow_strand_cluster.size() + 1 == cooked.shadow_source.offsets.size() && !cooked.shadow_source.points.empty()) {
        m.shadow_source = std::move(cooked.shadow_source);
        m.shadow_strand_cluster = std::move(cooked.shadow_strand_cluster);
    }
    stats_.grid_x = m.grid.dims.x;
    stats_.grid_y = m.grid.dims.y;
    stats_.grid_z = m.grid.dims.z;
    stats_.voxel = m.grid.voxel;
    stats_.tangent_spread = cooked.tangent_spread;
    stats_.auto_fiber_radius = cooked.auto_fiber_radius;
    bounds_min_ = p.bounds_min;
    bounds_max_ = p.bounds_max;
    // The lights and the body stay.
    if (!m.lights.empty()) m.gpu->set_lights(m.lights);
    if (m.body_mesh) upload_grid();
}

ShellRenderer::~ShellRenderer() = default;

OwnClusterDepth ShellRenderer::own_cluster_depth() const {
    const Impl& m = *impl_;
    std::vector<double> across, alpha;
    across.reserve(m.shells.samples.size());
    for (const LightingSample& q : m.shells.samples) {
        const glm::vec3 e1 = q.ellipse_axis();
        if (e1 == glm::vec3(0.0f) || !std::isfinite(q.tangent.w)) continue;  // no frame: not counted
        const glm::vec3 e2 = glm::cross(glm::normalize(glm::vec3(q.tangent)), e1);
        const float b = q.tangent.w;
        across.push_back(m.grid.integrate(glm::vec3(q.position) - b * e2, e2, 2.0f * b, 0.25f * m.grid.voxel));
    }
    alpha.reserve(m.shells.sectors.size());
    for (const ShellSector& sector : m.shells.sectors) alpha.push_back(sector.shadow.y);
    const auto median_or_zero = [](std::vector<double> v) { return v.empty() ? 0.0f : static_cast<float>(median(std::move(v))); };
    return {median_or_zero(std::move(across)), median_or_zero(std::move(alpha))};
}

void ShellRenderer::set_lights(std::span<const SrbfLight> lights) {
    impl_->gpu->set_lights(lights);
    impl_->lights.assign(lights.begin(), lights.end());
    impl_->shadow_key.valid = false;
}

void ShellRenderer::set_absorption(const AbsorptionMap* map) { impl_->gpu->set_absorption(map); }

void ShellRenderer::set_body(const BodyMesh* body, const glm::mat3& orientation, bool regrid) {
    Impl& m = *impl_;
    if (!body) m.body.reset();
    else if (m.body && m.body->vertices() == body->positions.size() && m.body->triangles() == body->triangles.size())
        m.body->update(*body, orientation);  // a new pose of the same mesh: no new programs
    else m.body = std::make_unique<BodyPass>(*body, orientation);
    if (body) m.body_mesh = *body;
    else m.body_mesh.reset();
    m.body_orientation = orientation;
    if (regrid) upload_grid();
}

bool ShellRenderer::has_body() const { return impl_->body != nullptr; }

std::uint32_t ShellRenderer::draw_body(const FrameView& view, int width, int height, std::span<const SrbfLight> lights) {
    if (!impl_->body) return 0;
    const std::uint32_t depth = impl_->body->draw(view, glm::vec2(0.0f), width, height, lights);
    glViewport(0, 0, width, height);
    return depth;
}

void ShellRenderer::set_shadow_grid(DensityGrid grid) {
    Impl& m = *impl_;
    if (glm::any(glm::lessThan(grid.dims, glm::ivec3(1))) || !(grid.voxel > 0.0f))
        throw Error::parameter("shadow grid", "it is empty");
    m.grid = std::move(grid);
    m.key_grid_made = false;
    upload_grid();
}

void ShellRenderer::upload_grid() {
    const glm::ivec3 dims = impl_->upload_grid();
    stats_.grid_x = dims.x, stats_.grid_y = dims.y, stats_.grid_z = dims.z;
    stats_.voxel = impl_->grid.voxel;
}

void ShellRenderer::set_cluster_transforms(std::span<const glm::mat4> transforms) {
    const auto start = Clock::now();
    Impl& m = *impl_;
    PreparedShells& p = m.shells;
    if (transforms.size() != p.clusters())
        throw Error::parameter("cluster transforms", std::to_string(transforms.size()) + " transforms for " +
                                                         std::to_string(p.clusters()) + " clusters");
    for (std::size_t c = 0; c < transforms.size(); ++c) {
        const glm::mat3 R(transforms[c]);
        const glm::vec3 t(transforms[c][3]);
        if (!(orthonormality_error(R) <= 1e-3f) || !(glm::determinant(R) > 0.0f) || !std::isfinite(t.x + t.y + t.z) ||
            !affine(transforms[c]))
            throw Error::parameter("cluster transform " + std::to_string(c), "must be a rotation and a translation");
    }
    if (m.cooked_instances.empty()) {  // the first motion: what later ones start from
        m.cooked_instances = p.instances;
        m.cooked_samples = p.samples;
    }
    for (std::size_t i = 0; i < p.instances.size(); ++i) {
        const ShellInstance& rest = m.cooked_instances[i];
        p.instances[i].model = transforms[rest.info.y] * rest.model;
    }
    const std::size_t rows = static_cast<std::size_t>(p.lighting_rows);
    for (std::size_t i = 0; i < p.samples.size(); ++i) {
        const glm::mat4& T = transforms[i / rows];
        const glm::mat3 R(T);
        const LightingSample& rest = m.cooked_samples[i];
        LightingSample& s = p.samples[i];
        s.position = glm::vec4(glm::vec3(T * glm::vec4(glm::vec3(rest.position), 1.0f)), rest.position.w);
        s.tangent = glm::vec4(R * glm::vec3(rest.tangent), rest.tangent.w);
        s.normal = glm::vec4(R * glm::vec3(rest.normal), rest.normal.w);
        s.tilt_mean = glm::vec4(R * glm::vec3(rest.tilt_mean), rest.tilt_mean.w);
        s.tilt_a = glm::vec4(R * glm::vec3(rest.tilt_a), rest.tilt_a.w);
        s.tilt_b = glm::vec4(R * glm::vec3(rest.tilt_b), rest.tilt_b.w);
    }
    m.gpu->set_placement(p.instances, p.samples);
    m.invalidate_shadows();
    move_timings_.placement_ms = wall_ms_since(start);
    move_timings_.shadow_grid_ms = 0.0;
    if (m.shadow_source.points.empty()) return;
    // The grid's strands moved with their clusters and voxelized again, with the body (set_body) in it.
    const auto regrid = Clock::now();
    const ShadowStrands& from = m.shadow_source;
    Strands& moved = m.strands_now();  // every strand's points are overwritten below
    for (std::size_t i = 0; i < m.shadow_strand_cluster.size(); ++i) {
        const glm::mat4& T = transforms[m.shadow_strand_cluster[i]];
        for (std::uint32_t k = from.offsets[i]; k < from.offsets[i + 1]; ++k)
            moved.points[k] = glm::vec3(T * glm::vec4(from.points[k], 1.0f));
    }
    m.grid = voxelize_strands(moved, glm::mat3(1.0f), kShadowGridSize);
    m.key_grid_made = false;
    upload_grid();
    move_timings_.shadow_grid_ms = wall_ms_since(regrid);
}

void ShellRenderer::draw(const Camera& camera, const ShellSettings& settings, bool floor_only) {
    validate(settings);
    draw_view(FrameView::of(camera), camera.width, camera.height, impl_->jitter, settings, floor_only);
}

void ShellRenderer::draw_view(const FrameView& view, int width, int height, glm::vec2 jitter, const ShellSettings& s,
                              bool floor_only) {
    glViewport(0, 0, width, height);
    glClearColor(s.background.x, s.background.y, s.background.z, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    ShellDraw d;
    d.target.viewport = glm::ivec4(0, 0, width, height);
    d.jitter = jitter;
    if (impl_->body && !floor_only) {  // the body first, opaque; the hair over it, behind it hidden
        d.target.scene_depth = impl_->body->draw(view, jitter, width, height, impl_->lights);
        d.target.depth_test = DepthTest::less_equal;
        d.target.over = true;
    }
    passes(view, d, s, floor_only);
    finish_frame(s, floor_only);
}

void ShellRenderer::draw_frame(const glm::mat4& view, const glm::mat4& projection, std::span<const SrbfLight> lights,
                               const ShellSettings& settings, const FrameTarget& target,
                               std::span<const glm::mat4> instances) {
    validate(settings);
    if (target.viewport.z < 1 || target.viewport.w < 1) throw Error::parameter("viewport", "must have a positive size");
    Impl& m = *impl_;
    const glm::mat4 identity(1.0f);
    if (instances.empty()) instances = std::span<const glm::mat4>(&identity, 1);
    if (m.instances.size() < instances.size()) m.instances.resize(instances.size());
    std::vector<FrameView> views;  // each instance's view of its own space, its scale and the lights turned into it
    std::vector<float> scales;
    std::vector<std::vector<SrbfLight>> turned_lights;
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const glm::mat4& M = instances[i];
        // Rigid with a uniform scale s: the columns of the linear part are orthogonal and of one length.
        const glm::mat3 A(M);
        const float scale = std::cbrt(glm::determinant(A));
        const glm::mat3 R = A / scale;
        const float off = orthonormality_error(R);
        if (!(scale > 0.0f) || !std::isfinite(scale) || off > 1e-3f || !affine(M))
            throw Error::parameter("instance " + std::to_string(i),
                                   "the transform must be a rotation, a translation and a uniform positive scale");
        // The hair is drawn in its own space: the view times the transform, the eye and the lights turned into it.
        FrameView v = FrameView::of(view * M, projection);
        std::vector<SrbfLight> turned(lights.begin(), lights.end());
        for (SrbfLight& l : turned) l.omega = glm::normalize(glm::transpose(R) * l.omega);
        views.push_back(v);
        scales.push_back(scale);
        turned_lights.push_back(std::move(turned));
    }
    // The k-buffer draws every instance's depths before any is shaded (its slots must hold the frame's nearest).
    const bool kbuffer = settings.compositing == Compositing::kbuffer;
    for (const ShellDraw::Phase phase : kbuffer ? std::vector<ShellDraw::Phase>{ShellDraw::Phase::depth, ShellDraw::Phase::shade}
                                                : std::vector<ShellDraw::Phase>{ShellDraw::Phase::all})
        for (std::size_t i = 0; i < instances.size(); ++i) {
            InstanceLights& il = m.instances[i];
            if (il.lighting.id() == 0)
                il.lighting = make_lighting_texture(m.gpu->lighting_rows, m.gpu->clusters);
            m.swap(il);
            if (il.lights != turned_lights[i]) {
                m.gpu->set_lights(turned_lights[i]);
                il.lights = turned_lights[i];
                m.shadow_key.valid = false;
            }
            ShellDraw d;
            d.target = target;
            d.first = i == 0 && phase != ShellDraw::Phase::shade;
            d.last = i + 1 == instances.size() && phase != ShellDraw::Phase::depth;
            d.distance_scale = scales[i];
            d.levels = &il.levels;
            d.phase = phase;
            try {
                passes(views[i], d, settings, false);
            } catch (...) {
                m.swap(il);
                throw;
            }
            m.swap(il);
        }
    finish_frame(settings, false);
}

void ShellRenderer::passes(const FrameView& view, const ShellDraw& draw, const ShellSettings& s, bool floor_only) {
    Impl& m = *impl_;
    if (!floor_only && s.compositing == Compositing::kbuffer && draw.phase == ShellDraw::Phase::all) {  // one instance
        ShellDraw depth = draw;
        depth.phase = ShellDraw::Phase::depth;
        depth.last = false;
        passes(view, depth, s, false);
        ShellDraw shade = draw;
        shade.phase = ShellDraw::Phase::shade;
        shade.first = false;
        passes(view, shade, s, false);
        return;
    }
    ShellDraw d = draw;
    d.detail = m.detail;
    ShellGpu& gpu = *m.gpu;
    if (!floor_only && d.phase == ShellDraw::Phase::depth) {  // the k-buffer's depths: no shadows or lighting needed
        if (d.first) {  // the frame's counts are the shading passes' (which begin no frame: they add to these)
            m.depth_pass_ms = 0;
            timings_.clusters_drawn = timings_.triangles_drawn = 0;
            timings_.clusters_at_level = {};
        }
        if (s.timed) glFinish();
        const auto t0 = Clock::now();
        m.shells_pass.draw(gpu, m.shells, view, d, s, false, m.lighting);
        if (s.timed) {
            glFinish();
            m.depth_pass_ms += wall_ms_since(t0);
        }
        check_errors("ShellRenderer::draw (k-buffer depths)");
        return;
    }
    // Shadow pass: only when the lights, the fibre radius or the samples it marches changed. It marches the samples the
    // lighting pass lights (its step), and every sample for the per-fragment lighting, which reads them all.
    const float radius = fiber_radius(s);
    if (!(radius > 0.0f) || !std::isfinite(radius)) throw Error::parameter("fiber_radius", "must be finite and > 0");
    const int step = m.lighting_step(s.lighting_step);
    const int shadow_step = s.lighting_per_fragment ? 1 : step;
    timings_.shadows_ms = 0;
    const bool inner = s.own_cluster_inner > 0.0f;  // (read with own_cluster_shadow only, which the pass does not know)
    const ShadowKey shadow_key{true, radius, shadow_step, s.shadow_neighbours, s.shadow_outward, inner};
    if (!floor_only && s.shadows && gpu.light_count > 0 && m.shadow_key != shadow_key) {
        timings_.shadows_ms = m.shadow.run(gpu, 2.0f * radius, shadow_step, s.shadow_neighbours, s.shadow_outward, inner);
        m.shadow_key = shadow_key;
        m.lighting_key.valid = false;  // the sums read the shadows
    }
    // The key lights' shadow volumes: only when the lights, the strands, the radius or their count changed.
    if (!floor_only && s.shadows && s.key_lights > 0 && gpu.light_count > 0) {
        const auto grid_start = Clock::now();
        if (m.make_key_grid()) timings_.shadows_ms += wall_ms_since(grid_start);
        timings_.shadows_ms += m.key_light.run(gpu, s.key_lights, 2.0f * radius);
    }

    // Lighting pass, then the shells; with s.timed, wall-clock per pass between glFinish calls.
    if (s.timed) glFinish();
    auto t_pass = Clock::now();
    timings_.lighting_wall_ms = timings_.shells_wall_ms = timings_.resolve_wall_ms = 0;
    ShellSettings lit = s;
    lit.lighting_step = timings_.lighting_step = step;
    // The levels of detail first: the lighting pass lights only the samples their meshes read (when the shells read the
    // sums per vertex, at the mesh rows); the shells then draw the levels picked here.
    std::span<const int> levels;
    if (!floor_only) {
        const std::vector<int>& picked = m.shells_pass.choose_levels(gpu, m.shells, view, d, lit, false);
        d.detail = ShellDraw::Detail::hold;
        // (Without a level of detail the levels keep what they held, which the full meshes drawn do not read.)
        if (s.lod_lighting && s.lod_pixels > 0.0f && ShellsPass::lighting_read(lit, gpu.lighting_rows, gpu.layout) == 1)
            levels = picked;
    }
    timings_.lighting_ran = !floor_only && m.lighting.run(gpu, lit, view.eye, m.lighting_key, levels);
    if (s.timed) {
        glFinish();
        timings_.lighting_wall_ms = timings_.lighting_ran ? wall_ms_since(t_pass) : 0.0;
        t_pass = Clock::now();
    }
    timings_.resolve_wall_ms = m.shells_pass.draw(gpu, m.shells, view, d, lit, floor_only, m.lighting);
    timings_.clusters_drawn = (d.first ? 0 : timings_.clusters_drawn) + m.shells_pass.clusters_drawn();
    timings_.triangles_drawn = (d.first ? 0 : timings_.triangles_drawn) + m.shells_pass.triangles_drawn();
    if (d.first) timings_.clusters_at_level = {};  // (the k-buffer's depth pass cleared them)
    for (int k = 0; k < kLodLevels; ++k)
        timings_.clusters_at_level[static_cast<std::size_t>(k)] += m.shells_pass.clusters_at_level()[static_cast<std::size_t>(k)];
    if (s.timed) {
        glFinish();
        timings_.shells_wall_ms = wall_ms_since(t_pass);
        if (d.phase == ShellDraw::Phase::shade && d.last) {  // the k-buffer's depth passes are part of the shells
            timings_.shells_wall_ms += m.depth_pass_ms;
            m.depth_pass_ms = 0;
        }
    }
    check_errors("ShellRenderer::draw");
}

void ShellRenderer::finish_frame(const ShellSettings& s, bool floor_only) {
    Impl& m = *impl_;
    if (FragmentLists* lists = m.shells_pass.lists(); lists && !floor_only && s.compositing == Compositing::exact) {
        lists->finish();
        if (lists->stats().dropped > 0 && !m.in_render)
            log_message(LogLevel::warning, "exact compositing dropped " + std::to_string(lists->stats().dropped) + " of " +
                                               std::to_string(lists->stats().fragments) + " fragments (storage for " +
                                               std::to_string(lists->stats().capacity) + "); the next frame has more");
    }
}

namespace {
// The lighting pass's texture as it is: per cluster, kLightingTexels rows of lighting_rows RGBA texels.
std::vector<float> lighting_texels(const ShellGpu& g) {
    std::vector<float> tex(static_cast<std::size_t>(g.lighting_rows) * g.clusters * kLightingTexels * 4);
    glGetTextureImage(g.lighting.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(tex.size() * sizeof(float)), tex.data());
    return tex;
}
// Float q (0 … 4 · kLightingTexels − 1) of cluster c's lighting sample `row` in lighting_texels' copy.
float lighting_float(const std::vector<float>& tex, const ShellGpu& g, std::size_t c, std::size_t row, int q) {
    const std::size_t y = c * kLightingTexels + static_cast<std::size_t>(q / 4);
    return tex[(y * static_cast<std::size_t>(g.lighting_rows) + row) * 4 + static_cast<std::size_t>(q % 4)];
}
}  // namespace

std::vector<float> ShellRenderer::read_lighting() const {
    const ShellGpu& g = *impl_->gpu;
    const std::vector<float> tex = lighting_texels(g);
    std::vector<float> out(g.clusters * g.lighting_rows * 27);
    for (std::size_t c = 0; c < g.clusters; ++c)
        for (int r = 0; r < g.lighting_rows; ++r)
            for (int q = 0; q < 27; ++q)
                out[(c * g.lighting_rows + r) * 27 + q] = lighting_float(tex, g, c, static_cast<std::size_t>(r), q);
    return out;
}

std::vector<std::array<glm::vec4, 5>> ShellRenderer::read_tangent_harmonics() const {
    const ShellGpu& g = *impl_->gpu;
    const std::vector<float> tex = lighting_texels(g);
    std::vector<std::array<glm::vec4, 5>> out(g.clusters * static_cast<std::size_t>(g.lighting_rows));
    constexpr int kTexel[5] = {8, 10, 11, 12, 13};  // shaders/gl/shell_lighting.comp
    for (std::size_t c = 0; c < g.clusters; ++c)
        for (int r = 0; r < g.lighting_rows; ++r)
            for (int h = 0; h < 5; ++h)
                for (int q = 0; q < 4; ++q)
                    out[c * g.lighting_rows + r][h][q] = lighting_float(tex, g, c, static_cast<std::size_t>(r), 4 * kTexel[h] + q);
    return out;
}

std::vector<glm::vec3> ShellRenderer::read_hot_spot() const {
    const ShellGpu& g = *impl_->gpu;
    const std::vector<float> tex = lighting_texels(g);
    std::vector<glm::vec3> out(g.clusters * static_cast<std::size_t>(g.lighting_rows));
    for (std::size_t c = 0; c < g.clusters; ++c)
        for (int r = 0; r < g.lighting_rows; ++r)
            for (int q = 0; q < 3; ++q)
                out[c * g.lighting_rows + r][q] = lighting_float(tex, g, c, static_cast<std::size_t>(r), 4 * kHotSpotTexel + q);
    return out;
}

std::vector<int> ShellRenderer::read_lights_lit() const {
    const ShellGpu& g = *impl_->gpu;
    const std::vector<float> tex = lighting_texels(g);
    // The samples the last lighting pass lit (its key's strides: the levels of detail's, or every sample).
    const std::vector<int> strides =
        impl_->lighting_key.strides.size() == g.clusters ? impl_->lighting_key.strides : lit_strides(g, {});
    std::vector<int> out;
    for (const glm::ivec2 sample : lit_samples(g.lighting_rows, timings_.lighting_step, strides)) {
        // Float 29: texel 7's second.
        out.push_back(static_cast<int>(
            lighting_float(tex, g, static_cast<std::size_t>(sample.x), static_cast<std::size_t>(sample.y), 29)));
    }
    return out;
}

double ShellRenderer::mean_lights_lit() const {
    const std::vector<int> lit = read_lights_lit();
    double sum = 0;
    for (const int n : lit) sum += n;
    return lit.empty() ? 0.0 : sum / static_cast<double>(lit.size());
}

int ShellRenderer::lighting_rows() const { return impl_->gpu->lighting_rows; }

std::vector<glm::vec2> ShellRenderer::read_shadows() const {
    const ShellGpu& g = *impl_->gpu;
    std::vector<glm::vec2> out(g.sample_count * static_cast<std::size_t>(g.light_count));
    if (!out.empty()) glGetNamedBufferSubData(g.shadows.id(), 0, static_cast<GLsizeiptr>(out.size() * sizeof(glm::vec2)), out.data());
    return out;
}

std::vector<glm::vec3> ShellRenderer::read_inner_depths() const {  // the layout of shaders/gl/inner_depths.glsl
    const ShellGpu& g = *impl_->gpu;
    std::vector<glm::vec2> raw(2 * g.sample_count);
    if (raw.empty() || g.light_count == 0) return {};
    glGetNamedBufferSubData(g.shadows.id(), static_cast<GLintptr>(g.sample_count * static_cast<std::size_t>(g.light_count) * sizeof(glm::vec2)),
                            static_cast<GLsizeiptr>(raw.size() * sizeof(glm::vec2)), raw.data());
    std::vector<glm::vec3> out(g.sample_count);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(raw[2 * i], raw[2 * i + 1].x);
    return out;
}

ShellRenderer::KeyVolume ShellRenderer::read_key_volume(int m) const {
    const KeyLightVolumes& k = impl_->gpu->key_lights;
    KeyVolume out;
    if (!k.valid || m < 0 || m >= k.count) return out;
    const std::size_t i = static_cast<std::size_t>(m);
    out.dims = k.dims[i];
    out.frame = k.frame[i];
    out.light = k.index[i];
    out.fibres.resize(static_cast<std::size_t>(out.dims.x) * out.dims.y * out.dims.z);
    glGetTextureImage(k.volume[i].id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.fibres.size() * sizeof(float)),
                      out.fibres.data());
    return out;
}

std::vector<glm::vec3> ShellRenderer::lighting_sample(std::size_t index) const {
    const LightingSample& s = impl_->shells.samples.at(index);
    return {glm::vec3(s.position), glm::vec3(s.tangent), glm::vec3(s.normal)};
}

const PreparedShells& ShellRenderer::prepared() const { return impl_->shells; }

void ShellRenderer::forget_detail() {
    impl_->shells_pass.forget_levels();
    for (InstanceLights& il : impl_->instances) il.levels.clear();
}

Image ShellRenderer::render(const Camera& camera, const ShellSettings& settings) {
    // One frame of the image. An exact frame that overflowed its fragment storage left holes: it is drawn
    // again, with the storage grown to what the frame counted. One that still overflows has met the GPU's
    // storage-block limit: it is drawn in tiles, each a part of the image seen through a projection that widens
    // that part to a whole frame (so each holds its share of the fragments), and a tile that still overflows is an
    // error. render() never returns an image with holes (draw(), the real-time path, warns and grows instead, so
    // that the next frame is whole).
    // The frames after the first have the same eye, lights and settings: they reuse its lighting sums whatever
    // settings.reuse_lighting says (exact: the jitter moves only the image).
    ShellSettings later = settings;
    later.reuse_lighting = true;
    const ShellSettings* frame_settings = &settings;
    timings_.tiles = 1;
    struct InRender {
        Impl& m;
        explicit InRender(Impl& impl) : m(impl) {
            m.in_render = true;
            m.detail = ShellDraw::Detail::fresh;  // the first frame picks the levels of detail as if nothing came before
        }
        ~InRender() {
            m.in_render = false;
            m.detail = ShellDraw::Detail::follow;
        }
    } in_render(*impl_);
    double lighting_ms = 0;  // the render's lighting pass (its first frame)
    const auto overflowed = [&] {
        const FragmentLists* lists = impl_->shells_pass.lists();
        return settings.compositing == Compositing::exact && lists && lists->stats().dropped > 0;
    };
    const auto draw_whole = [&](RenderTarget& target) {
        target.bind();
        draw(camera, *frame_settings);
        impl_->detail = ShellDraw::Detail::hold;  // every later frame and tile draws the first one's meshes
        lighting_ms += timings_.lighting_wall_ms;
        frame_settings = &later;
        if (!overflowed()) return target.read_back();
        draw(camera, later);
        if (!overflowed()) return target.read_back();
        return render_tiles(camera, later);
    };
    const int f = supersampling(settings);
    if (f == 1) {  // the blended modes' MSAA, or one exact or weighted frame (their targets hold one sample per pixel)
        RenderTarget target(camera.width, camera.height, GL_RGBA16F,
                            draws_single_sample(settings.compositing) ? 1 : settings.samples);
        Image image = draw_whole(target);
        timings_.lighting_wall_ms = lighting_ms;
        return image;
    }
    // The exact compositing keeps one fragment list per pixel, so it antialiases by supersampling: f × f
    // frames, f = round(√samples), each shifted by a sub-pixel offset so that together they sample the
    // pixel centres of an f-times finer grid (the same positions, the same memory as one frame), averaged
    // (a box filter). It costs f² frames.
    RenderTarget target(camera.width, camera.height, GL_RGBA16F, 1);
    Image sum;
    double shadows_ms = 0;  // the render's shadow pass, if it ran (on its first frame)
    for (int j = 0; j < f; ++j)
        for (int i = 0; i < f; ++i) {
            impl_->jitter = glm::vec2((i + 0.5f) / f - 0.5f, (j + 0.5f) / f - 0.5f);
            const Image frame = draw_whole(target);
            shadows_ms += timings_.shadows_ms;
            if (sum.empty()) sum = Image(frame.width, frame.height, frame.channels, 0.0f);
            for (std::size_t k = 0; k < frame.pixels.size(); ++k) sum.pixels[k] += frame.pixels[k];
        }
    impl_->jitter = glm::vec2(0.0f);
    timings_.shadows_ms = shadows_ms;
    timings_.lighting_wall_ms = lighting_ms;
    const float norm = 1.0f / static_cast<float>(f * f);
    for (float& v : sum.pixels) v *= norm;
    return sum;
}

Image ShellRenderer::render_tiles(const Camera& camera, const ShellSettings& settings) {
    Impl& m = *impl_;
    FragmentLists& lists = *m.shells_pass.lists();
    // n × n tiles, each expected to hold a 1/n² share of the frame's fragments with a quarter to spare; a tile that
    // still overflows (hair crowds the middle of a frame) is cut in four, and so on, down to 4 pixels a side.
    const double share = static_cast<double>(lists.stats().fragments) * 1.25 /
                         static_cast<double>(std::max<std::uint64_t>(lists.stats().max_capacity, 1));
    const int n = std::clamp(static_cast<int>(std::ceil(std::sqrt(share))), 2, std::min({16, camera.width, camera.height}));
    Image image(camera.width, camera.height, 4, 0.0f);
    const glm::mat4 view = camera.view(), projection = camera.projection();
    // The whole frame's sub-pixel shift, as ShellsPass applies it, in the whole frame's normalised device coordinates.
    const glm::mat4 shift = pixel_shift(m.jitter, camera.width, camera.height);
    int tiles = 0;
    // Draws the part [x0, x1) × [y0, y1) of the frame (pixels, rows from the top) through a projection that widens it to
    // the whole of normalised device space; true when its fragments fitted.
    const auto draw_tile = [&](int x0, int y0, int x1, int y1) {
        const int w = x1 - x0, h = y1 - y0;
        const float cx = -1.0f + static_cast<float>(x0 + x1) / camera.width;
        const float cy = 1.0f - static_cast<float>(y0 + y1) / camera.height;
        const glm::mat4 widen =
            glm::scale(glm::mat4(1.0f), glm::vec3(static_cast<float>(camera.width) / w, static_cast<float>(camera.height) / h, 1.0f)) *
            glm::translate(glm::mat4(1.0f), glm::vec3(-cx, -cy, 0.0f));
        RenderTarget target(w, h, GL_RGBA16F, 1);
        target.bind();
        for (int attempt = 0; attempt < 2; ++attempt) {  // the storage grows to the tile's own count, up to its limit
            draw_view(FrameView::of(view, widen * shift * projection), w, h,
                      glm::vec2(0.0f), settings, false);
            const FragmentListStats& st = lists.stats();
            if (st.dropped == 0) break;
            if (st.fragments > st.max_capacity) return false;
        }
        if (lists.stats().dropped > 0) return false;
        const Image part = target.read_back();
        for (int y = 0; y < h; ++y)
            std::copy_n(&part.pixels[static_cast<std::size_t>(y) * w * 4], static_cast<std::size_t>(w) * 4,
                        &image.pixels[(static_cast<std::size_t>(y0 + y) * camera.width + x0) * 4]);
        ++tiles;
        return true;
    };
    const std::function<void(int, int, int, int)> region = [&](int x0, int y0, int x1, int y1) {
        if (draw_tile(x0, y0, x1, y1)) return;
        if (x1 - x0 < 8 || y1 - y0 < 8)
            throw Error::parameter("exact compositing",
                                   "this " + std::to_string(camera.width) + "x" + std::to_string(camera.height) + " frame has " +
                                       std::to_string(lists.stats().fragments) + " fragments in its " + std::to_string(x1 - x0) +
                                       "x" + std::to_string(y1 - y0) + " tile at (" + std::to_string(x0) + ", " +
                                       std::to_string(y0) + "), and this GPU's fragment storage holds at most " +
                                       std::to_string(lists.stats().max_capacity) +
                                       " (its shader-storage block limit): use the sorted compositing");
        const int xm = (x0 + x1) / 2, ym = (y0 + y1) / 2;
        region(x0, y0, xm, ym);
        region(xm, y0, x1, ym);
        region(x0, ym, xm, y1);
        region(xm, ym, x1, y1);
    };
    for (int ty = 0; ty < n; ++ty)
        for (int tx = 0; tx < n; ++tx)
            region(camera.width * tx / n, camera.height * ty / n, camera.width * (tx + 1) / n, camera.height * (ty + 1) / n);
    timings_.tiles = tiles;
    return image;
}

FragmentCapture ShellRenderer::capture_fragments(const Camera& camera, const ShellSettings& settings, Image* resolved) {
    ShellSettings s = settings;
    s.compositing = Compositing::exact;
    s.samples = 1;
    // An overflowing first try grows the storage to what it counted, so the second holds every
    // fragment unless the GPU's storage-block limit is reached (then `dropped` says how many are missing).
    for (int attempt = 0; attempt < 2; ++attempt) {
        Image image = render(camera, s);
        if (resolved) *resolved = std::move(image);
        if (impl_->shells_pass.lists()->stats().dropped == 0) break;
    }
    return impl_->shells_pass.lists()->read_back();
}

void ShellRenderer::limit_fragment_storage(std::uint64_t nodes) { impl_->shells_pass.make_lists().limit_capacity(nodes); }

FragmentListStats ShellRenderer::fragment_list_stats() const {
    const FragmentLists* lists = impl_->shells_pass.lists();
    return lists ? lists->stats() : FragmentListStats{};
}

Image render_aov(ShellRenderer& renderer, const Camera& camera, const ScatteringAov& aov) {
    Image image = renderer.render(camera, aov.with);
    if (aov.without) {
        const Image less = renderer.render(camera, *aov.without);
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            if (i % image.channels != 3) image.pixels[i] -= less.pixels[i];
    }
    return image;
}

}  // namespace coif::gl
