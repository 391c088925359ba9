#include "online/shell_passes.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <numeric>

#include "models/core/error.h"
#include "shaders/envmap.h"
#include "shaders/lighting.h"

namespace coif::gl {
namespace {

using Clock = std::chrono::steady_clock;

// A grid of the strands' M (ShellGpu::set_grid's or set_key_grid's) on texture units 0 and 1, as the shadow marches read
// it (u_density, u_density_off, u_grid_min, u_grid_extent), and the fibres' diameter u_width.
void bind_density(const Program& p, const Texture& density, const Texture& density_off, glm::vec3 origin, glm::vec3 extent,
                  float fibre_width) {
    glBindTextureUnit(0, density.id());
    glUniform1i(p.uniform("u_density"), 0);
    glBindTextureUnit(1, density_off.id());
    glUniform1i(p.uniform("u_density_off"), 1);
    glUniform3fv(p.uniform("u_grid_min"), 1, &origin.x);
    glUniform3fv(p.uniform("u_grid_extent"), 1, &extent.x);
    glUniform1f(p.uniform("u_width"), fibre_width);
}

// The body on the shadow grid (SHADOW_BODY) on texture unit 2, with its optical depth per unit length and per ray.
void bind_body(const Program& p, const ShellGpu& gpu) {
    glBindTextureUnit(2, gpu.body.id());
    glUniform1i(p.uniform("u_body"), 2);
    glUniform1f(p.uniform("u_body_opacity"), kBodyOpacity / gpu.voxel);
    glUniform1f(p.uniform("u_body_max_depth"), kBodyMaxDepth);
}

}  // namespace

// ---- ShellGpu --------------------------------------------------------------------------------------

ShellGpu::ShellGpu(const PreparedShells& shells, const RecordAtlas& a, const DensityGrid& grid, const std::string& db_path)
    : layout(shells.layout),
      sample_count(shells.samples.size()),
      clusters(shells.clusters()),
      lighting_rows(shells.lighting_rows),
      atlas_width(a.width),
      atlas_height(a.height),
      tiles_per_row(a.tiles_per_row),
      views(a.views),
      hrir_length(a.hrir_length),
      atlas_lo(a.lo),
      atlas_scale(a.scale),
      re_norm(a.re_norm) {
    GLint max_tex = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
    if (a.width > max_tex || a.height > max_tex)
        throw Error(db_path, "records",
                    "the record atlas (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                        ") exceeds this GPU's texture size " + std::to_string(max_tex));
    atlas = make_texture_2d(GL_RGBA8, a.width, a.height, Sampling{GL_LINEAR, GL_CLAMP_TO_EDGE});
    glTextureSubImage2D(atlas.id(), 0, 0, 0, a.width, a.height, GL_RGBA, GL_UNSIGNED_BYTE, a.texels.data());

    set_grid(grid);

    vertices = make_buffer(shells.vertices.data(), shells.vertices.size() * sizeof(ShellVertex));
    {
        LodMeshes lod = lod_meshes(shells);
        indices = make_buffer(lod.indices.data(), lod.indices.size() * sizeof(std::uint32_t));
        lod_ranges = std::move(lod.ranges);
        lod_edge = std::move(lod.edge);
    }
    cluster_ids = make_buffer(shells.cluster_ids.data(), shells.cluster_ids.size() * sizeof(std::uint32_t));
    // The placements change when the hair moves (set_placement).
    instances = make_buffer(shells.instances.data(), shells.instances.size() * sizeof(ShellInstance), GL_DYNAMIC_STORAGE_BIT);
    sectors = make_buffer(shells.sectors.data(), shells.sectors.size() * sizeof(ShellSector));
    samples = make_buffer(shells.samples.data(), shells.samples.size() * sizeof(LightingSample), GL_DYNAMIC_STORAGE_BIT);
    vao = make_vertex_array();
    const GLuint v = vao.id();
    glVertexArrayVertexBuffer(v, 0, vertices.id(), 0, sizeof(ShellVertex));
    glVertexArrayVertexBuffer(v, 1, cluster_ids.id(), 0, sizeof(std::uint32_t));
    glVertexArrayBindingDivisor(v, 1, 1);
    glVertexArrayElementBuffer(v, indices.id());
    float_attribute(v, 0, 3, offsetof(ShellVertex, position), 0);
    float_attribute(v, 1, 3, offsetof(ShellVertex, tangent), 0);
    float_attribute(v, 2, 3, offsetof(ShellVertex, normal), 0);
    float_attribute(v, 3, 2, offsetof(ShellVertex, texcoord), 0);
    float_attribute(v, 4, 3, offsetof(ShellVertex, axis_normal), 0);
    glEnableVertexArrayAttrib(v, 5);
    glVertexArrayAttribIFormat(v, 5, 1, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(v, 5, 1);

    lighting = make_lighting_texture(lighting_rows, clusters);
    check_errors("ShellGpu upload");
}

Texture make_lighting_texture(int rows, std::size_t clusters) {
    Texture t = make_texture_2d(GL_RGBA32F, rows, static_cast<int>(clusters * kLightingTexels), Sampling{GL_LINEAR, GL_CLAMP_TO_EDGE});
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(t.id(), 0, GL_RGBA, GL_FLOAT, zero);
    return t;
}

namespace {
std::uint64_t next_stamp() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}
}  // namespace

void ShellGpu::set_lights(std::span<const SrbfLight> l) {
    lights_stamp = next_stamp();
    light_values.assign(l.begin(), l.end());
    lights = make_lights_buffer(l);
    light_count = static_cast<int>(l.size());
    // (T̃, n) per sample and light, then each sample's own cluster's depth toward the hair's inside as two vec2
    // (shaders/gl/shell_shadow.comp inner_depth): they go with the shadows wherever those are kept per instance.
    shadows = make_buffer(nullptr, (l.size() + 2) * sample_count * sizeof(glm::vec2));
}

void ShellGpu::set_placement(std::span<const ShellInstance> in, std::span<const LightingSample> s) {
    glNamedBufferSubData(instances.id(), 0, static_cast<GLsizeiptr>(in.size_bytes()), in.data());
    glNamedBufferSubData(samples.id(), 0, static_cast<GLsizeiptr>(s.size_bytes()), s.data());
    geometry_stamp = next_stamp();
}

void ShellGpu::set_grid(const DensityGrid& grid) {
    density = make_texture_3d(GL_RGBA32F, grid.dims, Sampling{GL_LINEAR, GL_CLAMP_TO_BORDER});
    glTextureSubImage3D(density.id(), 0, 0, 0, 0, grid.dims.x, grid.dims.y, grid.dims.z, GL_RGBA, GL_FLOAT, grid.diagonal_xy.data());
    density_off = make_texture_3d(GL_RG32F, grid.dims, Sampling{GL_LINEAR, GL_CLAMP_TO_BORDER});
    glTextureSubImage3D(density_off.id(), 0, 0, 0, 0, grid.dims.x, grid.dims.y, grid.dims.z, GL_RG, GL_FLOAT, grid.off_diagonal.data());
    grid_origin = grid.origin;
    grid_extent = grid.extent();
    voxel = grid.voxel;
    grid_stamp = next_stamp();
}

void ShellGpu::set_key_grid(const DensityGrid& grid) {
    key_density = make_texture_3d(GL_RGBA32F, grid.dims, Sampling{GL_LINEAR, GL_CLAMP_TO_BORDER});
    glTextureSubImage3D(key_density.id(), 0, 0, 0, 0, grid.dims.x, grid.dims.y, grid.dims.z, GL_RGBA, GL_FLOAT,
                        grid.diagonal_xy.data());
    key_density_off = make_texture_3d(GL_RG32F, grid.dims, Sampling{GL_LINEAR, GL_CLAMP_TO_BORDER});
    glTextureSubImage3D(key_density_off.id(), 0, 0, 0, 0, grid.dims.x, grid.dims.y, grid.dims.z, GL_RG, GL_FLOAT,
                        grid.off_diagonal.data());
    key_grid_origin = grid.origin;
    key_grid_extent = grid.extent();
    key_voxel = grid.voxel;
    grid_stamp = next_stamp();
    check_errors("ShellGpu::set_key_grid");
}

void ShellGpu::set_body(const std::vector<std::uint8_t>& occupancy, glm::ivec3 dims) {
    grid_stamp = next_stamp();
    body_on = !occupancy.empty();
    if (!body_on) return;
    body = make_texture_3d(GL_R8, dims, Sampling{GL_LINEAR, GL_CLAMP_TO_BORDER});
    std::vector<std::uint8_t> texels(occupancy.size());  // 0 or 1 → the normalised texel's 0 or 1 (255)
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = occupancy[i] ? 255 : 0;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of dims.x bytes, not padded to 4
    glTextureSubImage3D(body.id(), 0, 0, 0, 0, dims.x, dims.y, dims.z, GL_RED, GL_UNSIGNED_BYTE, texels.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    check_errors("ShellGpu::set_body");
}

void ShellGpu::set_absorption(const AbsorptionMap* map) {
    absorption_stamp = next_stamp();
    if (!map) {
        absorption_on = false;
        return;
    }
    const int n = static_cast<int>(clusters);
    if (map->clusters != n || map->samples < 1)
        throw Error::parameter("absorption map", "has " + std::to_string(map->clusters) + " cluster rows; the style has " +
                                                     std::to_string(n));
    std::vector<glm::vec4> texels(static_cast<std::size_t>(n) * lighting_rows);
    for (int c = 0; c < n; ++c)
        for (int r = 0; r < lighting_rows; ++r)
            texels[static_cast<std::size_t>(c) * lighting_rows + r] =
                glm::vec4(map->sample(c, static_cast<double>(r) / (lighting_rows - 1)), 0.0f);
    // Read with texelFetch; the wrap is GL's default.
    absorption = make_texture_2d(GL_RGBA32F, lighting_rows, n, Sampling{GL_NEAREST, GL_REPEAT});
    glTextureSubImage2D(absorption.id(), 0, 0, 0, lighting_rows, n, GL_RGBA, GL_FLOAT, texels.data());
    absorption_on = true;
    check_errors("ShellGpu::set_absorption");
}

// ---- ShadowPass ------------------------------------------------------------------------------------

double ShadowPass::run(const ShellGpu& gpu, float fibre_width, int lit_step, bool narrow_start, float outward, bool inner) const {
    const int used = lit_rows(gpu.lighting_rows, lit_step);  // validates
    glFinish();
    const auto t0 = Clock::now();
    if (gpu.body_on && !with_body_) with_body_ = std::make_unique<Program>(std::vector<std::string>{"shaders/gl/shell_shadow.comp"}, std::vector<std::string>{"SHADOW_BODY 1"});
    const Program& p = gpu.body_on ? *with_body_ : program_;
    p.use();
    if (gpu.body_on) bind_body(p, gpu);
    bind_density(p, gpu.density, gpu.density_off, gpu.grid_origin, gpu.grid_extent, fibre_width);
    glUniform1f(p.uniform("u_step"), gpu.voxel);
    glUniform1i(p.uniform("u_sample_count"), static_cast<GLint>(gpu.sample_count));
    glUniform1i(p.uniform("u_light_count"), gpu.light_count);
    glUniform1i(p.uniform("u_rays"), kShadowRays);
    glUniform1i(p.uniform("u_narrow_start"), narrow_start ? 1 : 0);
    glUniform1f(p.uniform("u_outward"), outward);
    glUniform1i(p.uniform("u_inner"), inner ? 1 : 0);
    glUniform1i(p.uniform("u_rows"), gpu.lighting_rows);
    glUniform1i(p.uniform("u_lit_step"), lit_step);
    glUniform1i(p.uniform("u_used"), used);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, gpu.samples.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, gpu.lights.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, gpu.shadows.id());
    const std::size_t marched = gpu.clusters * static_cast<std::size_t>(used) * static_cast<std::size_t>(gpu.light_count);
    glDispatchCompute(static_cast<GLuint>((marched + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (lit_step > 1) {  // the samples between the marched ones
        if (!fill_) fill_ = std::make_unique<Program>(std::vector<std::string>{"shaders/gl/shell_shadow.comp"}, std::vector<std::string>{"SHADOW_FILL 1"});
        fill_->use();
        glUniform1i(fill_->uniform("u_sample_count"), static_cast<GLint>(gpu.sample_count));
        glUniform1i(fill_->uniform("u_light_count"), gpu.light_count);
        glUniform1i(fill_->uniform("u_rows"), gpu.lighting_rows);
        glUniform1i(fill_->uniform("u_lit_step"), lit_step);
        const std::size_t pairs = gpu.sample_count * static_cast<std::size_t>(gpu.light_count);
        glDispatchCompute(static_cast<GLuint>((pairs + 63) / 64), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glFinish();
    return wall_ms_since(t0);
}

// ---- KeyLightPass ----------------------------------------------------------------------------------

int key_lights(const ShellGpu& gpu, const ShellSettings& s) {
    return s.shadows && s.key_lights > 0 && gpu.key_lights.valid && gpu.key_lights.wanted == s.key_lights ? gpu.key_lights.count
                                                                                                          : 0;
}

std::vector<int> key_light_indices(std::span<const SrbfLight> lights, int count) {
    if (count < 0 || count > kMaxKeyLights)
        throw Error::parameter("key_lights", "must be 0.." + std::to_string(kMaxKeyLights) + ", not " + std::to_string(count));
    std::vector<int> order(lights.size());
    std::iota(order.begin(), order.end(), 0);
    const auto energy = [&](int j) {
        return std::abs(glsl::luminance(lights[static_cast<std::size_t>(j)].L)) * glsl::srbf_integral(lights[static_cast<std::size_t>(j)].lambda);
    };
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return energy(a) > energy(b); });
    order.resize(std::min(order.size(), static_cast<std::size_t>(count)));
    return order;
}

double KeyLightPass::run(ShellGpu& gpu, int count, float fibre_width) {
    KeyLightVolumes& k = gpu.key_lights;
    if (k.valid && k.wanted == count && k.lights_stamp == gpu.lights_stamp && k.grid_stamp == gpu.grid_stamp &&
        k.width == fibre_width)
        return 0.0;
    glFinish();
    const auto t0 = Clock::now();
    const std::vector<int> keys = key_light_indices(gpu.light_values, count);
    k.count = static_cast<int>(keys.size());
    if (gpu.body_on && !with_body_)
        with_body_ = std::make_unique<Program>(std::vector<std::string>{"shaders/gl/shell_key_light.comp"},
                                               std::vector<std::string>{"SHADOW_BODY 1"});
    const Program& p = gpu.body_on ? *with_body_ : program_;
    p.use();
    bind_density(p, gpu.key_density, gpu.key_density_off, gpu.key_grid_origin, gpu.key_grid_extent, fibre_width);
    if (gpu.body_on) {  // read on the shadow grid, which holds it
        bind_body(p, gpu);
        glUniform3fv(p.uniform("u_body_min"), 1, &gpu.grid_origin.x);
        glUniform3fv(p.uniform("u_body_extent"), 1, &gpu.grid_extent.x);
        glUniform1f(p.uniform("u_body_step"), gpu.voxel);
    }
    for (int m = 0; m < k.count; ++m) {
        const SrbfLight& light = gpu.light_values[static_cast<std::size_t>(keys[static_cast<std::size_t>(m)])];
        const glm::vec3 l = glm::normalize(light.omega);
        const glm::vec3 e1 = glm::normalize(std::abs(l.x) < 0.9f ? glm::cross(l, glm::vec3(1, 0, 0)) : glm::cross(l, glm::vec3(0, 1, 0)));
        const glm::vec3 e2 = glm::cross(l, e1);
        // The fine grid's box in the light's axes.
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner = gpu.key_grid_origin + gpu.key_grid_extent * glm::vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            const glm::vec3 q(glm::dot(corner, e1), glm::dot(corner, e2), glm::dot(corner, l));
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
        }
        const glm::vec3 size = hi - lo;
        const float h = std::max(gpu.key_voxel, std::max({size.x, size.y, size.z}) / static_cast<float>(kKeyLightVolumeMax));
        const glm::ivec3 dims = glm::max(glm::ivec3(glm::ceil(size / h)), glm::ivec3(2));
        const glm::vec3 origin = lo.x * e1 + lo.y * e2 + lo.z * l;
        // Shells' space → texture coordinates: (p · axis − lo) / (dims h) per axis.
        const glm::vec3 span = glm::vec3(dims) * h;
        glm::mat4 frame(1.0f);
        for (int a = 0; a < 3; ++a) {
            const glm::vec3 axis = a == 0 ? e1 : a == 1 ? e2 : l;
            frame[0][a] = axis.x / span[a];
            frame[1][a] = axis.y / span[a];
            frame[2][a] = axis.z / span[a];
            frame[3][a] = -lo[a] / span[a];
        }
        Texture& volume = k.volume[static_cast<std::size_t>(m)];
        if (volume.id() == 0 || k.dims[static_cast<std::size_t>(m)] != dims)
            volume = make_texture_3d(GL_R16F, dims, Sampling{GL_LINEAR, GL_CLAMP_TO_EDGE});
        k.dims[static_cast<std::size_t>(m)] = dims;
        k.index[static_cast<std::size_t>(m)] = keys[static_cast<std::size_t>(m)];
        k.light[static_cast<std::size_t>(m)] = glm::vec4(l, light.lambda);
        k.frame[static_cast<std::size_t>(m)] = frame;
        glUniform3fv(p.uniform("u_origin"), 1, &origin.x);
        glUniform3fv(p.uniform("u_e1"), 1, &e1.x);
        glUniform3fv(p.uniform("u_e2"), 1, &e2.x);
        glUniform3fv(p.uniform("u_l"), 1, &l.x);
        glUniform1f(p.uniform("u_h"), h);
        glUniform3i(p.uniform("u_dims"), dims.x, dims.y, dims.z);
        glBindImageTexture(0, volume.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R16F);
        glDispatchCompute(static_cast<GLuint>((dims.x + 7) / 8), static_cast<GLuint>((dims.y + 7) / 8), 1);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    k.valid = true;
    k.wanted = count;
    k.lights_stamp = gpu.lights_stamp;
    k.grid_stamp = gpu.grid_stamp;
    k.width = fibre_width;
    check_errors("KeyLightPass");
    glFinish();
    return wall_ms_since(t0);
}

// ---- LightingPass ----------------------------------------------------------------------------------

void LightingPass::bind_tables(const Program& prog) const { tables_.bind(prog, 2); }

void LightingPass::bind_inputs(const Program& prog, const ShellGpu& gpu, const ShellSettings& s) const {
    bind_tables(prog);
    set_lighting_uniforms(prog, s.hair.fibre, s.hair.config);
    glUniform1i(prog.uniform("u_light_count"), gpu.light_count);
    glUniform1i(prog.uniform("u_shadows"), s.shadows && gpu.light_count > 0 ? 1 : 0);
    glUniform1i(prog.uniform("u_shadow_samples"), static_cast<GLint>(gpu.sample_count));
    glUniform1f(prog.uniform("u_own_inner"), s.own_cluster_shadow ? s.own_cluster_inner : 0.0f);
    glUniform1i(prog.uniform("u_absorption_on"), gpu.absorption_on ? 1 : 0);
    if (gpu.absorption_on) {
        glBindTextureUnit(2 + shading::kLutCount, gpu.absorption.id());
        glUniform1i(prog.uniform("u_absorption"), 2 + shading::kLutCount);
    }
    glUniform1f(prog.uniform("u_d_f"), s.hair.d_f);
    glUniform1f(prog.uniform("u_tangent_spread"), s.tangent_spread);  // < 0: the samples' measured tilts
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, gpu.samples.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, gpu.lights.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, gpu.shadows.id());
}

std::string LightingPass::tangents_define(const ShellSettings& s) {
    // Four tangents (shaders/lighting/fibre_tangents.glsl), each costing about one more pass; one when the
    // spread is 0.
    return "SHELL_TANGENTS " + std::to_string(s.tangent_spread != 0.0f ? 4 : 1);
}

bool LightingPass::tilt_pick(const ShellSettings& s) { return s.tilt_per_strip && s.tangent_spread != 0.0f; }

std::vector<std::string> LightingPass::variant_defines(const ShellSettings& s) {
    std::vector<std::string> defines = srbf_variant_defines(s.hair.config, s.hair.lobes, s.hair.multiple);
    defines.push_back(tangents_define(s));
    return defines;
}

int lit_rows(int rows, int step) {
    if (step >= 1 && rows >= 2 && (rows - 1) % step == 0) return (rows - 1) / step + 1;
    std::string divisors;
    for (int k = 1; k <= std::max(rows - 1, 1); ++k)
        if ((rows - 1) % k == 0) divisors += (divisors.empty() ? "" : ", ") + std::to_string(k);
    throw Error::parameter("lighting_step", "must divide the " + std::to_string(rows - 1) + " intervals between a cluster's " +
                                                std::to_string(rows) + " lighting samples (" + divisors + "), not " +
                                                std::to_string(step));
}

std::vector<int> lit_strides(const ShellGpu& gpu, std::span<const int> levels) {
    std::vector<int> strides(gpu.clusters, 1);
    for (std::size_t c = 0; c < levels.size() && c < strides.size(); ++c) strides[c] = lod_row_stride(levels[c], gpu.lighting_rows);
    return strides;
}

std::vector<glm::ivec2> lit_samples(int rows, int step, std::span<const int> strides) {
    const int used = lit_rows(rows, step);
    std::vector<glm::ivec2> out;
    for (std::size_t c = 0; c < strides.size(); ++c)
        for (int u = 0; u < used; ++u)
            if ((u * step) % strides[c] == 0 || u + 1 == used) out.emplace_back(static_cast<int>(c), u);
    return out;
}

bool LightingPass::run(const ShellGpu& gpu, const ShellSettings& s, const glm::vec3& eye, LightingKey& key,
                       std::span<const int> levels) {
    const std::vector<int> strides = lit_strides(gpu, levels);
    const float own_inner = s.own_cluster_shadow ? s.own_cluster_inner : 0.0f;
    const bool same = key.valid && shading::same_hair_parameters(key.hair, s.hair) && key.shadows == s.shadows &&
                      key.own_inner == own_inner && key.tangent_spread == s.tangent_spread && key.step == s.lighting_step && key.light_cull == s.light_cull &&
                      key.key_lights == key_lights(gpu, s) && key.hot_spot == hot_spot_variant(s) && key.eye == eye &&
                      key.lights_stamp == gpu.lights_stamp &&
                      key.absorption_stamp == gpu.absorption_stamp && key.geometry_stamp == gpu.geometry_stamp &&
                      key.strides == strides;
    if (same && s.reuse_lighting) return false;
    tables_.update(s.hair.fibre, s.hair.config);  // validates; rebuilds only on a change
    std::vector<std::string> defines = variant_defines(s);
    defines.push_back("LIGHTING_TEXELS " + std::to_string(kLightingTexels));
    defines.push_back("LIGHTING_HOT_TEXEL " + std::to_string(kHotSpotTexel));
    defines.push_back("SHELL_HOT_SPOT " + std::to_string(hot_spot_variant(s)));
    // Culling lights keeps each sample's estimates and its lights kept in arrays of the light count.
    const bool cull = s.light_cull > 0.0f && gpu.light_count > 0 && gpu.light_count <= kMaxCulledLights;
    if (cull) defines.push_back("SHELL_CULL_LIGHTS " + std::to_string(gpu.light_count));
    const int keys = key_lights(gpu, s);
    if (keys > 0) defines.push_back("SHELL_KEY_LIGHTS " + std::to_string(keys));
    std::string name;
    for (const std::string& d : defines) name += d + "|";
    auto& slot = programs_[name];
    if (!slot) slot = std::make_unique<Program>(std::vector<std::string>{"shaders/gl/shell_lighting.comp"}, defines);
    const Program& program = *slot;
    program.use();
    bind_inputs(program, gpu, s);
    // The samples lit, as (cluster, k) for the k-th of the cluster's lit rows: every one the levels' meshes read.
    const std::vector<glm::ivec2> samples = lit_samples(gpu.lighting_rows, s.lighting_step, strides);
    const GLuint invocations = static_cast<GLuint>(samples.size());
    const Buffer lit = make_buffer(samples.data(), std::max<std::size_t>(samples.size(), 1) * sizeof(glm::ivec2));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, lit.id());
    glUniform1i(program.uniform("u_invocations"), static_cast<GLint>(invocations));
    glUniform1i(program.uniform("u_rows"), gpu.lighting_rows);
    glUniform1i(program.uniform("u_step"), s.lighting_step);
    glUniform3fv(program.uniform("u_eye"), 1, &eye.x);
    if (cull) glUniform1f(program.uniform("u_light_cull"), s.light_cull);
    if (keys > 0) glUniform1iv(program.uniform("u_key_index"), keys, gpu.key_lights.index.data());
    glBindImageTexture(0, gpu.lighting.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute((invocations + 31) / 32, 1, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    key = {true, s.hair, s.shadows, own_inner, s.tangent_spread, s.lighting_step, s.light_cull, keys, hot_spot_variant(s), eye,
           gpu.lights_stamp, gpu.absorption_stamp, gpu.geometry_stamp, strides};
    return true;
}

// ---- ShellsPass ------------------------------------------------------------------------------------

const Program& ShellsPass::shading_program(Compositing mode, const ShellSettings& s, int lighting_rows, const DiskLayout& L,
                                           DepthTest depth, int keys, bool fold) {
    // The lighting sums are read per vertex when the lighting rows are the mesh rows (the varyings then
    // interpolate exactly what a per-fragment fetch would), per fragment otherwise.
    // Every lighting_step-th row lit is still a subset of the mesh rows, so the per-vertex read stays exact.
    const int lighting = lighting_read(s, lighting_rows, L);
    std::vector<std::string> defines{"SHELL_NEIGHBOURS " + std::to_string(s.neighbours),
                                     "SHELL_LIGHTING " + std::to_string(lighting), "SHELL_DEBUG " + std::to_string(s.debug),
                                     "SHELL_FOURIER " + std::to_string(s.fourier_order),
                                     "SHELL_OWN " + std::to_string(own_cluster_variant(s)),
                                     "SHELL_SCENE_DEPTH " + std::to_string(static_cast<int>(depth)),
                                     std::string("SHELL_FOLD ") + (fold ? "1" : "0"),
                                     std::string("SHELL_TILT_PICK ") + (LightingPass::tilt_pick(s) ? "1" : "0"),
                                     std::string("SHELL_SECTOR_PICK ") + (s.sector_per_strip ? "1" : "0"),
                                     "LIGHTING_TEXELS " + std::to_string(kLightingTexels),
                                     "LIGHTING_HOT_TEXEL " + std::to_string(kHotSpotTexel),
                                     "SHELL_HOT_SPOT " + std::to_string(hot_spot_variant(s)),
                                     std::string("SHELL_KEY_MEAN ") + (s.key_re_mean ? "1" : "0"),
                                     "SHELL_KEY_LIGHTS " + std::to_string(keys)};
    if (lighting == 2) {  // the per-fragment reference lights every fragment as the lighting pass lights a sample
        const std::vector<std::string> variant = LightingPass::variant_defines(s);
        defines.insert(defines.end(), variant.begin(), variant.end());
    }
    // The fragment shader of each compositing: exact appends to the lists, weighted accumulates, the others blend.
    const char* fragment = mode == Compositing::exact      ? "shaders/gl/shell_abuffer.frag"
                           : mode == Compositing::weighted ? "shaders/gl/shell_weighted.frag"
                           : mode == Compositing::kbuffer  ? "shaders/gl/shell_kbuffer.frag"
                                                           : "shaders/gl/shell.frag";
    if (mode == Compositing::kbuffer) defines.push_back("KBUFFER_SLOTS " + std::to_string(s.kbuffer_slots));
    std::string key = fragment;
    for (const std::string& d : defines) key += "|" + d;
    auto& slot = programs_[key];
    if (!slot) slot = std::make_unique<Program>(std::vector<std::string>{"shaders/gl/shell.vert", fragment}, defines);
    return *slot;
}

int ShellsPass::lighting_read(const ShellSettings& s, int lighting_rows, const DiskLayout& L) {
    return s.lighting_per_fragment ? 2 : lighting_rows == L.s_t * L.mesh_t + 1 ? 1 : 0;
}

std::vector<int>& ShellsPass::choose_levels(const ShellGpu& gpu, const PreparedShells& shells, const FrameView& view,
                                            const ShellDraw& d, const ShellSettings& s, bool floor_only) {
    const bool lod = !floor_only && s.lod_pixels > 0.0f;
    std::vector<int>& level = d.levels ? *d.levels : level_;
    // The k-buffer's shading pass draws the meshes its depth pass drew.
    const ShellDraw::Detail detail = d.phase == ShellDraw::Phase::shade ? ShellDraw::Detail::hold : d.detail;
    if (level.size() != shells.clusters() || (lod && detail == ShellDraw::Detail::fresh)) level.assign(shells.clusters(), 0);
    if (lod && detail != ShellDraw::Detail::hold) {
        if (prototype_boxes_.size() != shells.meshes.size()) prototype_boxes_ = prototype_boxes(shells);
        pick_levels(gpu, shells, view, cluster_boxes(shells, prototype_boxes_), d.target.viewport.w, s.lod_pixels, level);
    }
    return level;
}

void ShellsPass::pick_levels(const ShellGpu& gpu, const PreparedShells& shells, const FrameView& view,
                             std::span<const ClusterBox> boxes, int height, float budget_px, std::vector<int>& levels) const {
    // Pixels per unit of the shells' space at eye depth z: P₁₁ · height/2 · (the view's scale) / z (a perspective
    // projection), or without the division (an orthographic one, whose w does not depend on z).
    const bool perspective = view.projection[2][3] != 0.0f;
    const float per_unit = view.projection[1][1] * 0.5f * static_cast<float>(height) * glm::length(glm::vec3(view.view[0]));
    for (std::size_t c = 0; c < boxes.size(); ++c) {
        float depth = std::numeric_limits<float>::max();  // the box's nearest corner: the cluster's largest projection
        for (const glm::vec3& corner : boxes[c]) depth = std::min(depth, -(view.view * glm::vec4(corner, 1.0f)).z);
        if (perspective && !(depth > 1e-6f)) {  // the eye at or inside the box: full detail
            levels[c] = 0;
            continue;
        }
        const float scale = glm::length(glm::vec3(shells.instances[c].model[0]));
        std::array<float, kLodLevels> px{};
        for (int k = 0; k < kLodLevels; ++k)
            px[static_cast<std::size_t>(k)] =
                gpu.lod_edge[shells.cluster_proto[c]][static_cast<std::size_t>(k)] * scale * per_unit / (perspective ? depth : 1.0f);
        levels[c] = pick_lod(px, levels[c], budget_px);
    }
}

FragmentLists& ShellsPass::make_lists() {
    if (!lists_) lists_ = std::make_unique<FragmentLists>();
    return *lists_;
}

double ShellsPass::draw(const ShellGpu& gpu, const PreparedShells& shells, const FrameView& view, const ShellDraw& d,
                        const ShellSettings& s, bool floor_only, const LightingPass& lighting) {
    const DiskLayout& L = gpu.layout;
    const bool exact = !floor_only && s.compositing == Compositing::exact;
    const bool kbuffer = !floor_only && s.compositing == Compositing::kbuffer;
    const bool depth_pass = kbuffer && d.phase == ShellDraw::Phase::depth;  // the k-buffer's first pass
    // The weighted compositing, and the k-buffer's tail, which is the same blend.
    const bool weighted = !floor_only && (s.compositing == Compositing::weighted || kbuffer);
    const bool own_targets = exact || weighted;  // drawn into targets of the viewport's size, then resolved into the frame
    if (kbuffer && d.phase == ShellDraw::Phase::all)
        throw Error::parameter("compositing", "the k-buffer draws a frame in a depth pass and a shading pass");
    if (exact) make_lists();
    if (weighted && !weighted_) weighted_ = std::make_unique<WeightedBlend>();
    const FrameTarget& t = d.target;
    const int width = t.viewport.z, height = t.viewport.w;
    const DepthTest depth = floor_only || t.scene_depth == 0 ? DepthTest::none : t.depth_test;
    const Program* program = &floor_;
    const int keys = floor_only ? 0 : key_lights(gpu, s);  // lit apart, with their shadow volumes
    if (depth_pass) {
        const std::vector<std::string> defines{"KBUFFER_SLOTS " + std::to_string(s.kbuffer_slots),
                                               "SHELL_SCENE_DEPTH " + std::to_string(static_cast<int>(depth))};
        std::string key;
        for (const std::string& x : defines) key += x + "|";
        auto& slot = depth_programs_[key];
        if (!slot)
            slot = std::make_unique<Program>(std::vector<std::string>{"shaders/gl/shell.vert", "shaders/gl/shell_kbuffer_depth.frag"},
                                             defines);
        program = slot.get();
    } else if (!floor_only) {
        program = &shading_program(s.compositing, s, gpu.lighting_rows, L, depth, keys);
    }
    // The fold's program (ShellSettings::fold_level): the same but for SHELL_FOLD; the k-buffer's depth pass draws the
    // same meshes with its own.
    const bool can_fold = !floor_only && s.fold_level < kLodLevels && weighted && !s.lighting_per_fragment;
    const Program* fold_program = program;
    if (can_fold && !depth_pass) fold_program = &shading_program(s.compositing, s, gpu.lighting_rows, L, depth, keys, true);
    // A sub-pixel shift of the image (ShellRenderer::render's supersampling): x right, y down, in pixels.
    const glm::mat4 vp = pixel_shift(d.jitter, width, height) * view.projection * view.view;
    glm::vec2 depth_range{0.0f};  // the weighted compositing's eye distances (below)
    // Every uniform of a shading program but the per-draw ones below (the program's in use after).
    const auto bind = [&](const Program& prog) {
        prog.use();
        glUniformMatrix4fv(prog.uniform("u_view_projection"), 1, GL_FALSE, &vp[0][0]);
        if (depth != DepthTest::none) {  // (never for the floor)
            glBindTextureUnit(kSceneDepthUnit, t.scene_depth);
            glUniform1i(prog.uniform("u_scene_depth"), kSceneDepthUnit);
            // The lists' and the weighted targets' framebuffer is the viewport's size; a blended draw goes straight into
            // the host's framebuffer.
            const glm::ivec2 offset = own_targets ? glm::ivec2(t.viewport.x, t.viewport.y) : glm::ivec2(0);
            glUniform2i(prog.uniform("u_scene_depth_offset"), offset.x, offset.y);
        }
        if (depth_pass) {
            glUniform3fv(prog.uniform("u_eye"), 1, &view.eye.x);
        } else if (!floor_only) {
            glBindTextureUnit(0, gpu.atlas.id());
            glBindTextureUnit(1, gpu.lighting.id());
            glUniform1i(prog.uniform("u_records"), 0);
            glUniform1i(prog.uniform("u_lighting"), 1);
            glUniform1i(prog.uniform("u_tiles_per_row"), gpu.tiles_per_row);
            glUniform2f(prog.uniform("u_atlas_inv_size"), 1.0f / gpu.atlas_width, 1.0f / gpu.atlas_height);
            glUniform1i(prog.uniform("u_views"), gpu.views);
            glUniform4fv(prog.uniform("u_atlas_lo"), kAtlasParts, &gpu.atlas_lo[0].x);
            glUniform4fv(prog.uniform("u_atlas_scale"), kAtlasParts, &gpu.atlas_scale[0].x);
            glUniform1i(prog.uniform("u_hrir_length"), gpu.hrir_length);
            glUniform1i(prog.uniform("u_lighting_rows"), gpu.lighting_rows);
            glUniform1i(prog.uniform("u_lighting_used"), lit_rows(gpu.lighting_rows, s.lighting_step));
            glUniform1i(prog.uniform("u_lighting_height"), static_cast<GLint>(gpu.clusters * kLightingTexels));
            glUniform1i(prog.uniform("u_s_t"), L.s_t);
            glUniform1i(prog.uniform("u_s_u"), L.s_u);
            glUniform1i(prog.uniform("u_layers"), L.layers);
            glUniform1f(prog.uniform("u_kappa_shadow"), s.kappa_shadow);
            glUniform1f(prog.uniform("u_re_scale"), 1.0f / gpu.re_norm);
            glUniform3fv(prog.uniform("u_eye"), 1, &view.eye.x);
            if (s.lighting_per_fragment)
                lighting.bind_inputs(prog, gpu, s);
            else if (s.own_cluster_shadow) {
                lighting.bind_tables(prog);  // lut_own_cluster
                if (own_cluster_variant(s) == 2) glUniform1f(prog.uniform("u_d_f"), s.hair.d_f);
            }
            if (keys > 0) {  // their shadow volumes on the units after the scene's depth
                const KeyLightVolumes& k = gpu.key_lights;
                std::array<GLint, kMaxKeyLights> units{};
                for (int m = 0; m < keys; ++m) {
                    units[static_cast<std::size_t>(m)] = kSceneDepthUnit + 1 + m;
                    glBindTextureUnit(static_cast<GLuint>(kSceneDepthUnit + 1 + m), k.volume[static_cast<std::size_t>(m)].id());
                }
                glUniform1iv(prog.uniform("u_key_volume"), keys, units.data());
                // Each volume read key_toward_light voxels of the fine grid toward its light, and every slab's points
                // key_toward_camera voxels toward the camera (shaders/gl/key_light_volume.glsl).
                std::array<glm::mat4, kMaxKeyLights> reading{};
                for (int m = 0; m < keys; ++m) {
                    const auto i = static_cast<std::size_t>(m);
                    reading[i] = k.frame[i] * glm::translate(glm::mat4(1.0f), s.key_toward_light * gpu.key_voxel * glm::vec3(k.light[i]));
                }
                glUniformMatrix4fv(prog.uniform("u_key_frame"), keys, GL_FALSE, &reading[0][0][0]);
                glUniform1f(prog.uniform("u_key_toward_camera"), s.key_toward_camera * gpu.key_voxel);
                glUniform4fv(prog.uniform("u_key_light"), keys, &k.light[0].x);
                glUniform1iv(prog.uniform("u_key_index"), keys, k.index.data());
            }
        }
        if (exact) {
            glUniform1ui(prog.uniform("u_capacity"), static_cast<GLuint>(lists_->stats().capacity));
            glUniform1f(prog.uniform("u_distance_scale"), d.distance_scale);
        }
        if (kbuffer) glUniform1f(prog.uniform("u_distance_scale"), d.distance_scale);
        if (weighted && !depth_pass) glUniform2f(prog.uniform("u_depth_range"), depth_range.x, depth_range.y);
    };
    // Clusters wholly outside the view make no fragment: skipped, the image is the same. The weighted compositing
    // normalises its fragments' eye distances to the range of the clusters' boxes.
    std::vector<char> visible(shells.clusters(), 1);
    const bool lod = !floor_only && s.lod_pixels > 0.0f;
    const std::vector<int>& level = choose_levels(gpu, shells, view, d, s, floor_only);
    if (s.cull || weighted) {
        if (prototype_boxes_.size() != shells.meshes.size()) prototype_boxes_ = prototype_boxes(shells);
        const std::vector<ClusterBox> boxes = cluster_boxes(shells, prototype_boxes_);
        float nearest = std::numeric_limits<float>::max(), farthest = 0.0f;
        for (std::size_t c = 0; c < boxes.size(); ++c) {
            if (s.cull) visible[c] = box_in_view(vp, boxes[c]);
            if (weighted && visible[c])
                for (const glm::vec3& corner : boxes[c]) {
                    const float e = glm::distance(corner, view.eye);
                    nearest = std::min(nearest, e);
                    farthest = std::max(farthest, e);
                }
        }
        if (weighted && !depth_pass) {
            // A box's nearest corner can be nearer than any fragment (or behind the eye, within the box): clamped at 0.
            nearest = farthest > 0.0f ? std::max(0.0f, nearest) : 0.0f;
            depth_range = {nearest, 1.0f / std::max(farthest - nearest, 1e-6f)};
        }
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, gpu.instances.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, gpu.sectors.id());
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    if (exact) {  // append every fragment to its pixel's list; no blending, no colour output
        if (d.first) {
            glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_framebuffer_);
            lists_->begin(width, height);
        } else {
            lists_->bind();  // the shadow and lighting passes of this instance used the same units
        }
        glDisable(GL_BLEND);
    } else if (weighted) {  // accumulate every fragment, in any order (online/weighted_blend.h)
        if (d.first) {
            glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_framebuffer_);
            weighted_->begin(width, height, kbuffer ? s.kbuffer_slots : 0);
        } else {
            weighted_->bind();
        }
        if (kbuffer) {
            weighted_->bind_slots();
            if (depth_pass) {  // depths alone: no colour output, no blending
                glDisable(GL_BLEND);
                glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
            } else {
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);  // the depth pass's slots
            }
        }
    } else {
        glViewport(t.viewport.x, t.viewport.y, width, height);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over" (004 eq. 14)
    }
    glEnable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glBindVertexArray(gpu.vao.id());

    std::vector<std::size_t> order(shells.clusters());
    std::iota(order.begin(), order.end(), 0);
    if (s.compositing == Compositing::sorted) {
        std::vector<float> dist(order.size());
        for (std::size_t c = 0; c < order.size(); ++c) dist[c] = glm::distance(view.eye, shells.cluster_centre[c]);
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return dist[a] > dist[b]; });
    }
    bind(*program);
    // The uniforms each draw sets, of the program in use.
    struct Locations {
        GLint layer, layers, rho, inner_rho, fold_inner;
    };
    const auto locations = [&](const Program& p) {
        return Locations{floor_only ? -1 : p.uniform("u_layer"), floor_only ? -1 : p.uniform("u_layers"),
                         floor_only ? -1 : p.uniform("u_layer_rho"),
                         floor_only || depth_pass ? -1 : p.uniform("u_inner_rho"),
                         floor_only || depth_pass ? -1 : p.uniform("u_fold_inner")};
    };
    Locations loc = locations(*program);
    DiskLayout own = L;  // the drawn cluster's prototype's layout: its own layer count
    // Layer j of cluster c; with the fold's program, with layer j − 1 inside it when j > 0 (fold_inner 1) or alone (the
    // innermost of an odd count).
    const auto draw_layer = [&](std::size_t c, int j) {
        const MeshRange& r = gpu.lod_ranges[shells.cluster_proto[c]][static_cast<std::size_t>(j)][lod ? static_cast<std::size_t>(level[c]) : 0];
        triangles_ += static_cast<std::size_t>(r.count) / 3;
        if (loc.layer >= 0) glUniform1i(loc.layer, j);
        if (loc.rho >= 0) glUniform1f(loc.rho, static_cast<float>(own.layer_v(j + 1)));  // the layer mesh's own surface
        if (loc.inner_rho >= 0) glUniform1f(loc.inner_rho, static_cast<float>(own.layer_v(j)));
        if (loc.fold_inner >= 0) glUniform1f(loc.fold_inner, j > 0 ? 1.0f : 0.0f);
        glDrawElementsInstancedBaseVertexBaseInstance(
            GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(static_cast<std::uintptr_t>(r.first) * sizeof(std::uint32_t)), 1, r.base_vertex,
            static_cast<GLuint>(c));
    };
    const auto set_layers = [&](std::size_t c) {
        const int layers = static_cast<int>(shells.meshes[shells.cluster_proto[c]].size());
        if (layers != own.layers) {
            own.layers = layers;
            if (loc.layers >= 0) glUniform1i(loc.layers, layers);
        }
        return layers;
    };
    drawn_ = 0;
    triangles_ = 0;
    at_level_ = {};
    std::vector<std::size_t> folded;  // drawn after the others, with the fold's program
    for (std::size_t c : order) {
        if (!visible[c]) continue;
        ++drawn_;
        ++at_level_[lod ? static_cast<std::size_t>(level[c]) : 0];
        if (can_fold && level[c] >= s.fold_level) {
            folded.push_back(c);
            continue;
        }
        const int layers = set_layers(c);
        glCullFace(GL_FRONT);  // back faces (far side, seen through the core): outer → inner
        for (int j = layers - 1; j >= 0; --j) draw_layer(c, j);
        glCullFace(GL_BACK);   // front faces: inner → outer
        for (int j = 0; j < layers; ++j) draw_layer(c, j);
    }
    if (!folded.empty()) {
        if (fold_program != program) {
            bind(*fold_program);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, gpu.samples.id());  // the clusters' axes (shell.vert)
            loc = locations(*fold_program);
            own.layers = L.layers;
        }
        for (std::size_t c : folded) {
            const int layers = set_layers(c);
            // Pairs (layers − 1, layers − 2), …: the outer layer's mesh drawn; an odd count's innermost alone.
            glCullFace(GL_FRONT);
            for (int j = layers - 1; j >= 0; j -= 2) draw_layer(c, j);
            glCullFace(GL_BACK);
            for (int j = (layers - 1) % 2; j < layers; j += 2) draw_layer(c, j);
        }
    }
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    if (depth_pass) {
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glDepthMask(GL_TRUE);
        return 0;
    }
    double resolve_ms = 0;
    if (own_targets && d.last) {  // the lists' per-pixel sort and "over", or the weighted mean, into the caller's framebuffer
        if (exact) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        Clock::time_point t_resolve;
        if (s.timed) {
            glFinish();
            t_resolve = Clock::now();
        }
        glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target_framebuffer_));
        glViewport(t.viewport.x, t.viewport.y, width, height);
        if (exact)
            lists_->resolve(s.background, t.over, glm::ivec2(t.viewport.x, t.viewport.y));
        else
            weighted_->resolve(s.background, t.over, glm::ivec2(t.viewport.x, t.viewport.y));
        if (s.timed) {
            glFinish();
            resolve_ms = wall_ms_since(t_resolve);
        }
    }
    glDepthMask(GL_TRUE);
    return resolve_ms;
}

}  // namespace coif::gl
