#include "online/shell_renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include "models/core/error.h"
#include "models/strands.h"
#include "models/style_strands.h"
#include "offline/sector_generator.h"
#include "online/lighting_uniforms.h"
#include "online/shadow_grid.h"

namespace coif::gl {

namespace {

constexpr int kLightingTexels = 7;  // 27 floats of C_k, S_k per lighting sample
constexpr int kShadowGridSize = 64;   // voxels along the hair's longest axis (docs/renderer.md: error and cost)
constexpr int kShadowRays = 7;        // rays per SRBF lobe in the shadow pass (centre + a ring of 6)

// std430 mirrors of the GLSL structs.
struct GpuInstance {
    glm::mat4 model;
    glm::uvec4 info;
};
struct GpuSector {
    glm::uvec4 id{0};
    glm::vec4 weight{0};
    glm::vec4 shadow{0};
};
struct GpuSample {
    glm::vec4 position, tangent, normal;
};
struct Vertex {
    glm::vec3 position, tangent, normal;
    glm::vec2 texcoord;
    glm::vec3 axis_normal;
};
struct MeshRange {
    GLuint first = 0;  // index offset
    GLsizei count = 0;
    GLint base_vertex = 0;
    GLsizei vertex_count = 0;
};

glm::mat4 to_mat4(const glm::mat3& orientation, const Similarity& s) {
    const glm::mat3 r = glm::mat3_cast(glm::quat(s.rotation));
    glm::mat4 m(orientation * r * static_cast<float>(s.scale));
    m[3] = glm::vec4(orientation * glm::vec3(s.translation), 1.0f);
    return m;
}

}  // namespace

struct ShellRenderer::Impl {
    const SatfIndex* satf = nullptr;
    DiskLayout layout;
    Program floor{{"shaders/gl/shell.vert", "shaders/gl/shell_floor.frag"}};
    Program lighting{{"shaders/gl/shell_lighting.comp"}};
    Program shadow{{"shaders/gl/shell_shadow.comp"}};
    VertexArray vao;
    Buffer vertices, indices, cluster_ids, instances, sectors, samples, lights, shadows;
    Texture atlas, lighting_tex, density, absorption;
    bool absorption_on = false;
    DensityGrid grid;        // values dropped after upload; dims, origin and voxel kept
    float db_kappa = 0.6f;   // the database's κ (planar tracer)
    bool shadows_valid = false;
    float shadows_kappa = -1.0f;
    bool shadows_own = true;
    LightingTextures lighting_textures;  // the lighting module's tables (online/lighting_uniforms.h)
    std::vector<std::vector<MeshRange>> meshes;  // [prototype][layer]
    std::vector<std::size_t> cluster_proto;      // cluster → prototype slot
    std::vector<glm::vec3> cluster_centre;
    int tiles_per_row = 1, atlas_w = 1, atlas_h = 1, views = 32, hrir_length = 32;
    glm::vec2 jitter{0.0f};    // sub-pixel image shift of the next draw (render()'s supersampling), pixels
    glm::vec4 atlas_lo[3]{glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f)};  // value = lo + scale · texel
    glm::vec4 atlas_scale[3]{glm::vec4(1.0f), glm::vec4(1.0f), glm::vec4(1.0f)};
    int lighting_rows = 2;
    std::size_t sample_count = 0;
    int light_count = 0;
    // The shading programs, one per compile-time variant (shaders/gl/shell_shade.glsl), made on first use.
    std::map<std::string, std::unique_ptr<Program>> shading_programs;
    const Program& shading_program(bool abuffer, const ShellSettings& s);
    // Exact compositing (Compositing::exact, capture_fragments): made on first use.
    std::unique_ptr<FragmentLists> lists;
    // The dual-scattering tables of the last parameter set.
    std::vector<GpuSample> cpu_samples;
};

const Program& ShellRenderer::Impl::shading_program(bool abuffer, const ShellSettings& s) {
    // The lighting sums are read per vertex when the lighting rows are the mesh rows (the varyings then
    // interpolate exactly what a per-fragment fetch would), per fragment otherwise.
    const int lighting = s.lighting_per_fragment ? 2 : lighting_rows == layout.s_t * layout.mesh_t + 1 ? 1 : 0;
    const std::vector<std::string> defines{"SHELL_NEIGHBOURS " + std::to_string(s.neighbours),
                                           "SHELL_LIGHTING " + std::to_string(lighting), "SHELL_DEBUG " + std::to_string(s.debug),
                                           "SHELL_FOURIER " + std::to_string(s.fourier_order)};
    std::string key = abuffer ? "abuffer" : "blend";
    for (const std::string& d : defines) key += "|" + d;
    auto& slot = shading_programs[key];
    if (!slot)
        slot = std::make_unique<Program>(
            std::vector<std::string>{"shaders/gl/shell.vert", abuffer ? "shaders/gl/shell_abuffer.frag" : "shaders/gl/shell.frag"},
            defines);
    return *slot;
}

glm::mat3 style_orientation(const HairStyle& style) {
    glm::dvec3 sum(0.0);
    for (const Cluster& c : style.clusters) {
        if (!c.shape) continue;
        sum += c.placement.apply(c.shape->position(1.0)) - c.placement.apply(c.shape->position(0.0));
    }
    StrandStats st;
    st.mean_root_to_tip = glm::length(sum) > 0 ? glm::normalize(sum) : glm::dvec3(0, -1, 0);
    return hang_axis_rotation(st);
}

ShellRenderer::ShellRenderer(const HairStyle& style, const SatfIndex& satf, const glm::mat3& orientation,
                             int lighting_rows_per_hsv, Strands* sampled_strands)
    : impl_(std::make_unique<Impl>()) {
    const auto start = std::chrono::steady_clock::now();
    Impl& m = *impl_;
    m.satf = &satf;
    m.layout = style.layout;
    const DiskLayout& L = m.layout;
    const HrirDatabase& db = satf.database();
    const AngleGrids& g = db.params().grids;
    if (style.clusters.empty()) throw Error(style.name, "clusters", "the style has no clusters");
    m.views = g.views;
    m.hrir_length = g.hrir_length;

    // ---- the record atlas and per-record means ------------------------------------------------------
    const std::size_t records = db.size();
    const std::size_t tiles = records * 3;
    m.tiles_per_row = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles) * (g.views + 2) / (g.hrir_length + 2))));
    m.tiles_per_row = std::max(1, m.tiles_per_row);
    const int tile_rows = static_cast<int>((tiles + m.tiles_per_row - 1) / m.tiles_per_row);
    m.atlas_w = m.tiles_per_row * (g.hrir_length + 2);
    m.atlas_h = tile_rows * (g.views + 2);
    GLint max_tex = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
    if (m.atlas_w > max_tex || m.atlas_h > max_tex)
        throw Error(db.path().string(), "records",
                    "the record atlas (" + std::to_string(m.atlas_w) + "x" + std::to_string(m.atlas_h) +
                        ") exceeds this GPU's texture size " + std::to_string(max_tex));
    std::vector<glm::vec4> atlas(static_cast<std::size_t>(m.atlas_w) * m.atlas_h, glm::vec4(0.0f));
    std::vector<std::uint8_t> atlas_part(atlas.size(), 0);  // which part (0, 1, 2) each texel belongs to
    glm::vec4 part_lo[3], part_hi[3];
    for (int part = 0; part < 3; ++part) {
        part_lo[part] = glm::vec4(std::numeric_limits<float>::max());
        part_hi[part] = glm::vec4(std::numeric_limits<float>::lowest());
    }
    std::vector<float> mean_alpha(records), mean_a0(records);
    const int X = g.hrir_length, V = g.views;
    for (std::size_t rec = 0; rec < records; ++rec) {
        const std::vector<float> r = db.record(rec);
        double sa = 0, s0 = 0;
        for (int v = 0; v < V; ++v)
            for (int x = 0; x < X; ++x) {
                sa += r[g.alpha_offset(v) + x];
                s0 += r[g.re_offset(v, 0) + x];
            }
        mean_alpha[rec] = static_cast<float>(sa / (V * X));
        mean_a0[rec] = static_cast<float>(s0 / (V * X));
        for (int part = 0; part < 3; ++part) {
            const std::size_t tile = rec * 3 + part;
            const int ox = static_cast<int>(tile % m.tiles_per_row) * (X + 2);
            const int oy = static_cast<int>(tile / m.tiles_per_row) * (V + 2);
            for (int py = 0; py < V + 2; ++py)
                for (int px = 0; px < X + 2; ++px) {
                    const int v = (py - 1 + V) % V, x = (px - 1 + X) % X;  // periodic borders
                    glm::vec4 texel(0.0f);
                    for (int ch = 0; ch < 4; ++ch) {
                        const int value = part * 4 + ch;  // 0 = α, 1.. = re coefficient value − 1
                        if (value == 0) texel[ch] = r[g.alpha_offset(v) + x];
                        // re's first 9 coefficients (a0, a1, b1 … a4, b4); a database of a lower order
                        // leaves the rest zero, one of a higher order is read to order 4.
                        else if (value <= 9 && value - 1 < g.coefficients()) texel[ch] = r[g.re_offset(v, value - 1) + x];
                    }
                    const std::size_t at = static_cast<std::size_t>(oy + py) * m.atlas_w + ox + px;
                    atlas[at] = texel;
                    atlas_part[at] = static_cast<std::uint8_t>(part);
                    part_lo[part] = glm::min(part_lo[part], texel);
                    part_hi[part] = glm::max(part_hi[part], texel);
                }
        }
    }
    // Stored as 8-bit unorm texels with one affine range per channel of each part (value = lo + scale ·
    // texel): bilinear filtering and the neighbour blend commute with the affine map, so the shader decodes
    // once per sector. Half the memory of RGBA16F and llvmpipe's faster 8-bit filtering; the quantisation's
    // effect on the image (51 dB against RGBA16F) is in docs/renderer.md.
    for (int part = 0; part < 3; ++part) {
        glm::vec4 lo = part_lo[part], hi = part_hi[part];
        for (int ch = 0; ch < 4; ++ch)
            if (!(hi[ch] > lo[ch])) hi[ch] = lo[ch] + 1.0f;  // a constant (or unused) channel
        m.atlas_lo[part] = lo;
        m.atlas_scale[part] = hi - lo;  // the fetch returns texel / 255
    }
    std::vector<std::uint8_t> atlas8(atlas.size() * 4);
    for (std::size_t t = 0; t < atlas.size(); ++t) {
        const int part = atlas_part[t];
        for (int ch = 0; ch < 4; ++ch) {
            const float u = (atlas[t][ch] - m.atlas_lo[part][ch]) / m.atlas_scale[part][ch] * 255.0f;
            atlas8[t * 4 + ch] = static_cast<std::uint8_t>(std::clamp(std::lround(u), 0L, 255L));
        }
    }
    {
        GLuint id = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &id);
        m.atlas = Texture(id);
        glTextureStorage2D(id, 1, GL_RGBA8, m.atlas_w, m.atlas_h);
        glTextureSubImage2D(id, 0, 0, 0, m.atlas_w, m.atlas_h, GL_RGBA, GL_UNSIGNED_BYTE, atlas8.data());
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    const double sum_alpha = std::accumulate(mean_alpha.begin(), mean_alpha.end(), 0.0);
    const double sum_a0 = std::accumulate(mean_a0.begin(), mean_a0.end(), 0.0);
    stats_.re_norm = sum_alpha > 0 && sum_a0 > 0 ? static_cast<float>(sum_a0 / sum_alpha) : 1.0f;

    // ---- prototypes: meshes, sectors (features → look-up), shadow sums --------------------------------
    std::vector<std::size_t> proto_slot(style.clusters.size(), SIZE_MAX);
    std::vector<std::size_t> prototypes;
    for (const Cluster& c : style.clusters)
        if (proto_slot[c.prototype] == SIZE_MAX) {
            proto_slot[c.prototype] = prototypes.size();
            prototypes.push_back(c.prototype);
        }
    const std::size_t per_proto = L.sector_count();
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<GpuSector> gpu_sectors(prototypes.size() * per_proto);
    const double lambda = L.gaussian_width;
    m.meshes.resize(prototypes.size());
    for (std::size_t p = 0; p < prototypes.size(); ++p) {
        const Cluster& proto = style.clusters[prototypes[p]];
        const GeneralizedCylinder& shape = *proto.shape;
        for (int j = 0; j < L.layers; ++j) {
            const LayerMesh mesh = layer_mesh(shape, L, j);
            MeshRange range;
            range.first = static_cast<GLuint>(indices.size());
            range.count = static_cast<GLsizei>(mesh.indices.size());
            range.base_vertex = static_cast<GLint>(vertices.size());
            range.vertex_count = static_cast<GLsizei>(mesh.position.size());
            for (std::size_t v = 0; v < mesh.position.size(); ++v) {
                const Frame f = shape.frame(mesh.texcoord[v].y);
                vertices.push_back({mesh.position[v], mesh.tangent[v], mesh.normal[v], mesh.texcoord[v], glm::vec3(f.normal)});
            }
            indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
            m.meshes[p].push_back(range);
            stats_.triangles += mesh.indices.size() / 3;
        }
        const std::vector<SectorDensity> grids = cluster_sector_densities(shape, L, *proto.density);
        std::vector<float> rows(per_proto * kRawFeatureCount);
        for (std::size_t s = 0; s < per_proto; ++s) {
            const SectorRef ref = sector_ref(L, s);
            const SectorShape sh = sector_shape(shape, L, ref.plane, ref.layer, ref.sector);
            const RawFeatures f = raw_sector_features(grids[s], sh.depth / lambda, sh.width / std::max(sh.depth, 1e-12));
            std::copy(f.begin(), f.end(), rows.begin() + static_cast<std::ptrdiff_t>(s * kRawFeatureCount));
        }
        const std::vector<SectorMatch> matches = satf.match_all(rows);
        std::vector<float> sector_alpha(per_proto, 0.0f);
        for (std::size_t s = 0; s < per_proto; ++s) {
            const SectorMatch& mt = matches[s];
            std::vector<int> order(mt.k);
            std::iota(order.begin(), order.end(), 0);
            std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return mt.weight[a] > mt.weight[b]; });
            GpuSector& gs = gpu_sectors[p * per_proto + s];
            for (int n = 0; n < std::min(mt.k, kMaxShellNeighbours); ++n) {
                gs.id[n] = mt.id[order[n]];
                gs.weight[n] = mt.weight[order[n]];
            }
            double a = 0;
            for (int n = 0; n < mt.k; ++n) a += mt.weight[n] * mean_alpha[mt.id[n]];
            sector_alpha[s] = static_cast<float>(a);
        }
        for (int i = 0; i <= L.s_t; ++i)
            for (int k = 0; k < L.s_u; ++k) {
                float outer = 0.0f;  // Σ ᾱ of the layers outside layer j (004 eq. 12's χ(k))
                for (int j = L.layers - 1; j >= 0; --j) {
                    const std::size_t s = L.sector_index(i, j, k);
                    gpu_sectors[p * per_proto + s].shadow.x = outer;
                    outer += sector_alpha[s];
                }
            }
    }
    stats_.prototypes = prototypes.size();
    stats_.sectors = gpu_sectors.size();
    stats_.records = records;
    stats_.atlas_width = m.atlas_w;
    stats_.atlas_height = m.atlas_h;

    // ---- clusters: instances, lighting samples, bounds ------------------------------------------------
    if (lighting_rows_per_hsv < 0 || lighting_rows_per_hsv > kMaxMeshSubdivision)
        throw Error::parameter("lighting rows per HSV", "must be 0.." + std::to_string(kMaxMeshSubdivision));
    m.lighting_rows = L.s_t * (lighting_rows_per_hsv > 0 ? lighting_rows_per_hsv : L.mesh_t) + 1;
    std::vector<GpuInstance> instances;
    std::vector<GpuSample> samples;
    std::vector<std::uint32_t> cluster_ids;
    bounds_min_ = glm::vec3(std::numeric_limits<float>::max());
    bounds_max_ = glm::vec3(std::numeric_limits<float>::lowest());
    for (std::size_t c = 0; c < style.clusters.size(); ++c) {
        const Cluster& cl = style.clusters[c];
        const std::size_t p = proto_slot[cl.prototype];
        const glm::mat4 model = to_mat4(orientation, cl.placement);
        const glm::mat3 rot(model);
        instances.push_back({model, glm::uvec4(static_cast<std::uint32_t>(p * per_proto), static_cast<std::uint32_t>(c), 0, 0)});
        cluster_ids.push_back(static_cast<std::uint32_t>(c));
        m.cluster_proto.push_back(p);
        const GeneralizedCylinder& shape = *cl.shape;
        m.cluster_centre.push_back(glm::vec3(model * glm::vec4(glm::vec3(shape.position(0.5)), 1.0f)));
        for (int r = 0; r < m.lighting_rows; ++r) {
            const double t = static_cast<double>(r) / (m.lighting_rows - 1);
            const Frame f = shape.frame(t);
            glm::vec4 position = model * glm::vec4(glm::vec3(shape.position(t)), 1.0f);
            position.w = static_cast<float>(cl.placement.scale * std::max(shape.a(t), shape.b(t)));
            samples.push_back({position,
                               glm::vec4(glm::normalize(rot * glm::vec3(f.tangent)), 0.0f),
                               glm::vec4(glm::normalize(rot * glm::vec3(f.normal)), 0.0f)});
        }
        const MeshRange& outer = m.meshes[p].back();
        for (GLsizei v = 0; v < outer.vertex_count; ++v) {
            const std::size_t vi = static_cast<std::size_t>(outer.base_vertex + v);
            const glm::vec3 w = glm::vec3(model * glm::vec4(vertices[vi].position, 1.0f));
            bounds_min_ = glm::min(bounds_min_, w);
            bounds_max_ = glm::max(bounds_max_, w);
        }
    }
    stats_.clusters = style.clusters.size();
    m.sample_count = samples.size();
    m.cpu_samples = samples;
    stats_.lighting_samples = samples.size();

    // ---- shadow grid (decision 5) ----------------------------------------------------------------------
    {
        StrandSampling sampling;
        Strands strands = sample_strands(style, sampling);
        stats_.shadow_strands = strands.strand_count();
        m.grid = voxelize_strands(strands, orientation, L.gaussian_width, kShadowGridSize);
        if (sampled_strands) *sampled_strands = std::move(strands);
        m.db_kappa = static_cast<float>(db.params().tracer.kappa);
        stats_.grid_x = m.grid.dims.x;
        stats_.grid_y = m.grid.dims.y;
        stats_.grid_z = m.grid.dims.z;
        stats_.voxel = m.grid.voxel;
        GLuint id = 0;
        glCreateTextures(GL_TEXTURE_3D, 1, &id);
        m.density = Texture(id);
        glTextureStorage3D(id, 1, GL_R32F, m.grid.dims.x, m.grid.dims.y, m.grid.dims.z);
        glTextureSubImage3D(id, 0, 0, 0, 0, m.grid.dims.x, m.grid.dims.y, m.grid.dims.z, GL_RED, GL_FLOAT, m.grid.values.data());
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            glTextureParameteri(id, wrap, GL_CLAMP_TO_BORDER);
        const float zero[4] = {0, 0, 0, 0};
        glTextureParameterfv(id, GL_TEXTURE_BORDER_COLOR, zero);
        m.grid.values = {};
    }

    // ---- upload ---------------------------------------------------------------------------------------
    m.vertices = make_buffer(vertices.data(), vertices.size() * sizeof(Vertex));
    m.indices = make_buffer(indices.data(), indices.size() * sizeof(std::uint32_t));
    m.cluster_ids = make_buffer(cluster_ids.data(), cluster_ids.size() * sizeof(std::uint32_t));
    m.instances = make_buffer(instances.data(), instances.size() * sizeof(GpuInstance));
    m.sectors = make_buffer(gpu_sectors.data(), gpu_sectors.size() * sizeof(GpuSector));
    m.samples = make_buffer(samples.data(), samples.size() * sizeof(GpuSample));
    m.vao = make_vertex_array();
    const GLuint vao = m.vao.id();
    glVertexArrayVertexBuffer(vao, 0, m.vertices.id(), 0, sizeof(Vertex));
    glVertexArrayVertexBuffer(vao, 1, m.cluster_ids.id(), 0, sizeof(std::uint32_t));
    glVertexArrayBindingDivisor(vao, 1, 1);
    glVertexArrayElementBuffer(vao, m.indices.id());
    const auto attrib = [&](GLuint loc, GLint n, std::size_t offset) { float_attribute(vao, loc, n, offset, 0); };
    attrib(0, 3, offsetof(Vertex, position));
    attrib(1, 3, offsetof(Vertex, tangent));
    attrib(2, 3, offsetof(Vertex, normal));
    attrib(3, 2, offsetof(Vertex, texcoord));
    attrib(4, 3, offsetof(Vertex, axis_normal));
    glEnableVertexArrayAttrib(vao, 5);
    glVertexArrayAttribIFormat(vao, 5, 1, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao, 5, 1);
    {
        GLuint id = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &id);
        m.lighting_tex = Texture(id);
        glTextureStorage2D(id, 1, GL_RGBA32F, m.lighting_rows, static_cast<GLsizei>(style.clusters.size() * kLightingTexels));
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    check_errors("ShellRenderer upload");
    stats_.prepare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

ShellRenderer::~ShellRenderer() = default;

void ShellRenderer::set_lights(std::span<const SrbfLight> lights) {
    impl_->lights = make_lights_buffer(lights);
    impl_->light_count = static_cast<int>(lights.size());
    impl_->shadows = make_buffer(nullptr, lights.size() * impl_->sample_count * sizeof(glm::vec2));
    impl_->shadows_valid = false;
}

void ShellRenderer::set_absorption(const AbsorptionMap* map) {
    Impl& m = *impl_;
    if (!map) {
        m.absorption_on = false;
        return;
    }
    const int clusters = static_cast<int>(m.cluster_proto.size());
    if (map->clusters != clusters || map->samples < 1)
        throw Error::parameter("absorption map", "has " + std::to_string(map->clusters) + " cluster rows; the style has " +
                                                     std::to_string(clusters));
    std::vector<glm::vec4> texels(static_cast<std::size_t>(clusters) * m.lighting_rows);
    for (int c = 0; c < clusters; ++c)
        for (int r = 0; r < m.lighting_rows; ++r)
            texels[static_cast<std::size_t>(c) * m.lighting_rows + r] =
                glm::vec4(map->sample(c, static_cast<double>(r) / (m.lighting_rows - 1)), 0.0f);
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    m.absorption = Texture(id);
    glTextureStorage2D(id, 1, GL_RGBA32F, m.lighting_rows, clusters);
    glTextureSubImage2D(id, 0, 0, 0, m.lighting_rows, clusters, GL_RGBA, GL_FLOAT, texels.data());
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    m.absorption_on = true;
    check_errors("ShellRenderer::set_absorption");
}

void ShellRenderer::draw(const Camera& camera, const ShellSettings& s, bool floor_only) {
    Impl& m = *impl_;
    if (s.neighbours < 1 || s.neighbours > kMaxShellNeighbours)
        throw Error::parameter("neighbours", "must be 1.." + std::to_string(kMaxShellNeighbours));
    if (s.fourier_order < 1 || s.fourier_order > 4) throw Error::parameter("fourier_order", "must be 1..4");
    const DiskLayout& L = m.layout;
    glViewport(0, 0, camera.width, camera.height);
    glClearColor(s.background.x, s.background.y, s.background.z, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    // ---- shadow pass (only when the lights or κ changed) ---------------------------------------------
    const float kappa = s.kappa_between >= 0.0f ? s.kappa_between : m.db_kappa;
    timings_.shadows_ms = 0;
    if (!floor_only && s.shadows && m.light_count > 0 &&
        (!m.shadows_valid || m.shadows_kappa != kappa || m.shadows_own != s.own_cluster_shadow)) {
        // Timed on the CPU around glFinish: llvmpipe's GL_TIME_ELAPSED does not cover this dispatch, and
        // the pass runs only when the lights change, so the synchronisation costs nothing per frame.
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        m.shadow.use();
        glBindTextureUnit(0, m.density.id());
        glUniform1i(m.shadow.uniform("u_density"), 0);
        const glm::vec3 extent = m.grid.extent();
        glUniform3fv(m.shadow.uniform("u_grid_min"), 1, &m.grid.origin.x);
        glUniform3fv(m.shadow.uniform("u_grid_extent"), 1, &extent.x);
        glUniform1f(m.shadow.uniform("u_step"), m.grid.voxel);
        glUniform1f(m.shadow.uniform("u_kappa"), kappa);
        glUniform1i(m.shadow.uniform("u_sample_count"), static_cast<GLint>(m.sample_count));
        glUniform1i(m.shadow.uniform("u_light_count"), m.light_count);
        glUniform1i(m.shadow.uniform("u_rays"), kShadowRays);
        glUniform1i(m.shadow.uniform("u_own"), s.own_cluster_shadow ? 1 : 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.samples.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m.lights.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m.shadows.id());
        const std::size_t pairs = m.sample_count * static_cast<std::size_t>(m.light_count);
        glDispatchCompute(static_cast<GLuint>((pairs + 63) / 64), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glFinish();
        timings_.shadows_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        m.shadows_valid = true;
        m.shadows_kappa = kappa;
        m.shadows_own = s.own_cluster_shadow;
    }

    // ---- lighting pass ---------------------------------------------------------------------------
    using Clock = std::chrono::steady_clock;
    const auto wall_ms = [](Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); };
    if (s.timed) glFinish();
    auto t_pass = Clock::now();
    timings_.lighting_wall_ms = timings_.shells_wall_ms = timings_.resolve_wall_ms = 0;
    // What the lighting pass and the per-fragment lighting reference (ShellSettings::lighting_per_fragment)
    // read: the lighting module's tables and parameters, the lights, their shadows, the painted σa.
    const auto set_light_uniforms = [&](const Program& prog) {
        m.lighting_textures.bind(prog, 2);
        set_lighting_uniforms(prog, s.hair.fibre, s.hair.config);
        glUniform1i(prog.uniform("u_light_count"), m.light_count);
        glUniform1i(prog.uniform("u_lobes"), s.hair.lobes);
        glUniform1i(prog.uniform("u_multiple"), s.hair.multiple ? 1 : 0);
        glUniform1i(prog.uniform("u_shadows"), s.shadows && m.light_count > 0 ? 1 : 0);
        glUniform1i(prog.uniform("u_absorption_on"), m.absorption_on ? 1 : 0);
        if (m.absorption_on) {
            glBindTextureUnit(2 + shading::kLutCount, m.absorption.id());
            glUniform1i(prog.uniform("u_absorption"), 2 + shading::kLutCount);
        }
        glUniform1f(prog.uniform("u_d_f"), s.hair.d_f);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m.lights.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m.shadows.id());
    };
    if (!floor_only) m.lighting_textures.update(s.hair.fibre, s.hair.config);  // validates; rebuilds only on a change
    if (!floor_only) {
        m.lighting.use();
        set_light_uniforms(m.lighting);
        glUniform1i(m.lighting.uniform("u_sample_count"), static_cast<GLint>(m.sample_count));
        glUniform1i(m.lighting.uniform("u_rows"), m.lighting_rows);
        glUniform3fv(m.lighting.uniform("u_eye"), 1, &camera.eye.x);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m.samples.id());
        glBindImageTexture(0, m.lighting_tex.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(static_cast<GLuint>((m.sample_count + 31) / 32), 1, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }

    if (s.timed) {
        glFinish();
        timings_.lighting_wall_ms = floor_only ? 0.0 : wall_ms(t_pass);
        t_pass = Clock::now();
    }

    // ---- shells ------------------------------------------------------------------------------------
    const bool exact = !floor_only && s.compositing == Compositing::exact;
    if (exact && !m.lists) m.lists = std::make_unique<FragmentLists>();
    const Program& prog = floor_only ? m.floor : m.shading_program(exact, s);
    prog.use();
    // A sub-pixel shift of the image (render()'s supersampling): x right, y down, in pixels.
    const glm::vec3 shift(2.0f * m.jitter.x / camera.width, -2.0f * m.jitter.y / camera.height, 0.0f);
    const glm::mat4 vp = glm::translate(glm::mat4(1.0f), shift) * camera.projection() * camera.view();
    glUniformMatrix4fv(prog.uniform("u_view_projection"), 1, GL_FALSE, &vp[0][0]);
    if (!floor_only) {
        glBindTextureUnit(0, m.atlas.id());
        glBindTextureUnit(1, m.lighting_tex.id());
        glUniform1i(prog.uniform("u_records"), 0);
        glUniform1i(prog.uniform("u_lighting"), 1);
        glUniform1i(prog.uniform("u_tiles_per_row"), m.tiles_per_row);
        glUniform2f(prog.uniform("u_atlas_inv_size"), 1.0f / m.atlas_w, 1.0f / m.atlas_h);
        glUniform1i(prog.uniform("u_views"), m.views);
        glUniform4fv(prog.uniform("u_atlas_lo"), 3, &m.atlas_lo[0].x);
        glUniform4fv(prog.uniform("u_atlas_scale"), 3, &m.atlas_scale[0].x);
        glUniform1i(prog.uniform("u_hrir_length"), m.hrir_length);
        glUniform1i(prog.uniform("u_lighting_rows"), m.lighting_rows);
        glUniform1i(prog.uniform("u_lighting_height"), static_cast<GLint>(m.cluster_proto.size() * kLightingTexels));
        glUniform1i(prog.uniform("u_s_t"), L.s_t);
        glUniform1i(prog.uniform("u_s_u"), L.s_u);
        glUniform1i(prog.uniform("u_layers"), L.layers);
        glUniform1f(prog.uniform("u_kappa_shadow"), s.kappa_shadow);
        glUniform1f(prog.uniform("u_re_scale"), 1.0f / stats_.re_norm);
        glUniform3fv(prog.uniform("u_eye"), 1, &camera.eye.x);
        if (s.lighting_per_fragment) set_light_uniforms(prog);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m.instances.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m.sectors.id());
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    GLint target_framebuffer = 0;
    if (exact) {  // append every fragment to its pixel's list; no blending, no colour output
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_framebuffer);
        m.lists->begin(camera.width, camera.height);
        glUniform1ui(prog.uniform("u_capacity"), static_cast<GLuint>(m.lists->stats().capacity));
        glDisable(GL_BLEND);
    } else {
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied "over" (004 eq. 14)
    }
    glEnable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glBindVertexArray(m.vao.id());

    std::vector<std::size_t> order(m.cluster_proto.size());
    std::iota(order.begin(), order.end(), 0);
    if (s.compositing == Compositing::sorted) {
        std::vector<float> dist(order.size());
        for (std::size_t c = 0; c < order.size(); ++c) dist[c] = glm::distance(camera.eye, m.cluster_centre[c]);
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return dist[a] > dist[b]; });
    }
    const GLint layer_loc = floor_only ? -1 : prog.uniform("u_layer");
    const auto draw_layer = [&](std::size_t c, int j) {
        const MeshRange& r = m.meshes[m.cluster_proto[c]][static_cast<std::size_t>(j)];
        if (layer_loc >= 0) glUniform1i(layer_loc, j);
        glDrawElementsInstancedBaseVertexBaseInstance(
            GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(static_cast<std::uintptr_t>(r.first) * sizeof(std::uint32_t)), 1, r.base_vertex,
            static_cast<GLuint>(c));
    };
    for (std::size_t c : order) {
        glCullFace(GL_FRONT);  // back faces (far side, seen through the core): outer → inner
        for (int j = L.layers - 1; j >= 0; --j) draw_layer(c, j);
        glCullFace(GL_BACK);   // front faces: inner → outer
        for (int j = 0; j < L.layers; ++j) draw_layer(c, j);
    }
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    timings_.resolve_wall_ms = 0;
    if (exact) {  // the per-pixel sort and "over" of the lists, into the caller's framebuffer
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        Clock::time_point t_resolve;
        if (s.timed) {
            glFinish();
            t_resolve = Clock::now();
        }
        glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target_framebuffer));
        glViewport(0, 0, camera.width, camera.height);
        m.lists->resolve(s.background);
        if (s.timed) {
            glFinish();
            timings_.resolve_wall_ms = wall_ms(t_resolve);
        }
    }
    glDepthMask(GL_TRUE);
    if (s.timed) {
        glFinish();
        timings_.shells_wall_ms = wall_ms(t_pass);
    }
    check_errors("ShellRenderer::draw");
    if (exact) {
        m.lists->finish();
        if (m.lists->stats().dropped > 0)
            std::fprintf(stderr, "coif: exact compositing dropped %llu of %llu fragments (storage for %llu); the next frame has more\n",
                         static_cast<unsigned long long>(m.lists->stats().dropped),
                         static_cast<unsigned long long>(m.lists->stats().fragments),
                         static_cast<unsigned long long>(m.lists->stats().capacity));
    }
}

std::vector<float> ShellRenderer::read_lighting() const {
    const Impl& m = *impl_;
    const std::size_t clusters = m.cluster_proto.size();
    std::vector<float> tex(static_cast<std::size_t>(m.lighting_rows) * clusters * kLightingTexels * 4);
    glGetTextureImage(m.lighting_tex.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(tex.size() * sizeof(float)), tex.data());
    std::vector<float> out(clusters * m.lighting_rows * 27);
    for (std::size_t c = 0; c < clusters; ++c)
        for (int r = 0; r < m.lighting_rows; ++r)
            for (int q = 0; q < 27; ++q) {
                const std::size_t y = c * kLightingTexels + q / 4;
                out[(c * m.lighting_rows + r) * 27 + q] = tex[(y * m.lighting_rows + r) * 4 + q % 4];
            }
    return out;
}

int ShellRenderer::lighting_rows() const { return impl_->lighting_rows; }

std::vector<glm::vec2> ShellRenderer::read_shadows() const {
    const Impl& m = *impl_;
    std::vector<glm::vec2> out(m.sample_count * static_cast<std::size_t>(m.light_count));
    if (!out.empty()) glGetNamedBufferSubData(m.shadows.id(), 0, static_cast<GLsizeiptr>(out.size() * sizeof(glm::vec2)), out.data());
    return out;
}

std::vector<glm::vec3> ShellRenderer::lighting_sample(std::size_t index) const {
    const GpuSample& s = impl_->cpu_samples.at(index);
    return {glm::vec3(s.position), glm::vec3(s.tangent), glm::vec3(s.normal)};
}

Image ShellRenderer::render(const Camera& camera, const ShellSettings& settings) {
    const int f = supersampling(settings);
    if (f == 1) {  // the blended modes' MSAA, or one exact frame (its lists hold one sample per pixel)
        RenderTarget target(camera.width, camera.height, GL_RGBA16F,
                            settings.compositing == Compositing::exact ? 1 : settings.samples);
        target.bind();
        draw(camera, settings);
        return target.read_back();
    }
    // The exact compositing keeps one fragment list per pixel, so it antialiases by supersampling: f × f
    // frames, f = round(√samples), each shifted by a sub-pixel offset so that together they sample the
    // pixel centres of an f-times finer grid (the same positions, the same memory as one frame), averaged
    // (a box filter). It costs f² frames.
    RenderTarget target(camera.width, camera.height, GL_RGBA16F, 1);
    target.bind();
    Image sum;
    double shadows_ms = 0;  // the render's shadow pass, if it ran (on its first frame)
    for (int j = 0; j < f; ++j)
        for (int i = 0; i < f; ++i) {
            impl_->jitter = glm::vec2((i + 0.5f) / f - 0.5f, (j + 0.5f) / f - 0.5f);
            draw(camera, settings);
            shadows_ms += timings_.shadows_ms;
            const Image frame = target.read_back();
            if (sum.empty()) sum = Image(frame.width, frame.height, frame.channels, 0.0f);
            for (std::size_t k = 0; k < frame.pixels.size(); ++k) sum.pixels[k] += frame.pixels[k];
        }
    impl_->jitter = glm::vec2(0.0f);
    timings_.shadows_ms = shadows_ms;
    const float norm = 1.0f / static_cast<float>(f * f);
    for (float& v : sum.pixels) v *= norm;
    return sum;
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
        if (impl_->lists->stats().dropped == 0) break;
    }
    return impl_->lists->read_back();
}

FragmentListStats ShellRenderer::fragment_list_stats() const {
    return impl_->lists ? impl_->lists->stats() : FragmentListStats{};
}

}  // namespace coif::gl
