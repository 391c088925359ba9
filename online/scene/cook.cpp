#include "online/scene/cook.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <chrono>
#include <functional>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <tuple>

#include "models/core/error.h"
#include "models/sector_features.h"
#include "models/style_strands.h"
#include "online/shells/shadow_grid.h"

namespace coif {
namespace {


// A record's 12 atlas channels at every (view, x), view-major: α and re's first 9 coefficients (a database of a
// lower order leaves the rest zero; one of a higher order is read to order 4).
std::vector<AtlasTexels> record_texels(const HrirDatabase& db, std::size_t rec) {
    const AngleGrids& g = db.params().grids;
    const std::vector<float> r = db.record(rec);
    std::vector<AtlasTexels> out(static_cast<std::size_t>(g.views) * g.hrir_length);
    for (int v = 0; v < g.views; ++v)
        for (int x = 0; x < g.hrir_length; ++x) {
            AtlasTexels& t = out[static_cast<std::size_t>(v) * g.hrir_length + x];
            for (int part = 0; part < kAtlasParts; ++part)
                for (int ch = 0; ch < 4; ++ch) {
                    const int value = atlas_value_index(part, ch);
                    float f = 0.0f;
                    if (value == 0) f = r[g.alpha_offset(v) + x];
                    else if (value <= kAtlasReCoefficients && value - 1 < g.coefficients())
                        f = r[g.re_offset(v, value - 1) + x];
                    t[part * 4 + ch] = f;
                }
        }
    return out;
}

// The best kMaxShellNeighbours of a look-up, best first, and the match's mean α (Σ weight · ᾱ over all k).
ShellSector shell_sector(const SectorMatch& mt, std::span<const float> mean_alpha, float* sector_alpha) {
    std::vector<int> order(mt.k);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return mt.weight[a] > mt.weight[b]; });
    ShellSector gs;
    for (int n = 0; n < std::min(mt.k, gl::kMaxShellNeighbours); ++n) {
        gs.id[n] = mt.id[order[n]];
        gs.weight[n] = mt.weight[order[n]];
    }
    double a = 0;
    for (int n = 0; n < mt.k; ++n) a += mt.weight[n] * mean_alpha[mt.id[n]];
    *sector_alpha = static_cast<float>(a);
    return gs;
}

}  // namespace

float sector_thinning(const SectorMatch& match, double sector_density, const HrirDatabase& db) {
    double record = 0, weights = 0;
    for (int n = 0; n < match.k; ++n) {
        record += match.weight[n] * db.features(match.id[n])[kMeanDensityColumn];
        weights += match.weight[n];
    }
    record = weights > 0 ? record / weights : 0;
    if (!(record > 1e-6) || !std::isfinite(sector_density)) return 1.0f;
    return static_cast<float>(std::clamp(sector_density / record, 0.0, 1.0));  // a sector without fibres: none drawn
}

DatabaseAtlasStats database_atlas_stats(const HrirDatabase& db) {
    const AngleGrids& g = db.params().grids;
    DatabaseAtlasStats s;
    std::array<glm::vec4, kAtlasParts> hi{};
    s.lo.fill(glm::vec4(std::numeric_limits<float>::max()));
    hi.fill(glm::vec4(std::numeric_limits<float>::lowest()));
    s.mean_alpha.resize(db.size());
    s.mean_a0.resize(db.size());
    const double texels = static_cast<double>(g.views) * g.hrir_length;
    for (std::size_t rec = 0; rec < db.size(); ++rec) {
        double sa = 0, s0 = 0;
        for (const AtlasTexels& t : record_texels(db, rec)) {
            sa += t[0];
            s0 += t[1];
            for (int part = 0; part < kAtlasParts; ++part)
                for (int ch = 0; ch < 4; ++ch) {
                    s.lo[part][ch] = std::min(s.lo[part][ch], t[part * 4 + ch]);
                    hi[part][ch] = std::max(hi[part][ch], t[part * 4 + ch]);
                }
        }
        s.mean_alpha[rec] = static_cast<float>(sa / texels);
        s.mean_a0[rec] = static_cast<float>(s0 / texels);
    }
    for (int part = 0; part < kAtlasParts; ++part) {
        for (int ch = 0; ch < 4; ++ch)
            if (!(hi[part][ch] > s.lo[part][ch])) hi[part][ch] = s.lo[part][ch] + 1.0f;  // a constant (or unused) channel
        s.scale[part] = hi[part] - s.lo[part];
    }
    const double sum_alpha = std::accumulate(s.mean_alpha.begin(), s.mean_alpha.end(), 0.0);
    const double sum_a0 = std::accumulate(s.mean_a0.begin(), s.mean_a0.end(), 0.0);
    s.re_norm = sum_alpha > 0 && sum_a0 > 0 ? static_cast<float>(sum_a0 / sum_alpha) : 1.0f;
    return s;
}

namespace {
// A database record's atlas tiles, quantised with the database-wide ranges (record_atlas.h record_tiles).
std::vector<std::uint8_t> database_record_tiles(const HrirDatabase& db, std::uint32_t r, const DatabaseAtlasStats& stats) {
    const AngleGrids& g = db.params().grids;
    const std::vector<AtlasTexels> texels = record_texels(db, r);
    return record_tiles(g.views, g.hrir_length, stats.lo, stats.scale,
                        [&](int v, int x) { return texels[static_cast<std::size_t>(v) * g.hrir_length + x]; });
}

// The atlas of `records` (checked against the database) with atlas record i's tiles from `tile(i)`, and the means and
// re_norm of `stats`: pack_record_atlas, with or without a cache's tiles.
RecordAtlas record_atlas_of(const HrirDatabase& db, std::span<const std::uint32_t> records, const DatabaseAtlasStats& stats,
                            const std::function<const std::vector<std::uint8_t>&(std::size_t)>& tile) {
    const AngleGrids& g = db.params().grids;
    for (const std::uint32_t r : records)
        if (r >= db.size()) throw Error(db.path(), "records", "record " + std::to_string(r) + " is out of range");
    RecordAtlas a = place_record_tiles(records.size(), g.views, g.hrir_length, stats.lo, stats.scale, tile);
    for (const std::uint32_t r : records) {
        a.mean_alpha.push_back(stats.mean_alpha[r]);
        a.mean_a0.push_back(stats.mean_a0[r]);
    }
    a.re_norm = stats.re_norm;
    return a;
}
}  // namespace

RecordAtlas pack_record_atlas(const HrirDatabase& db, std::span<const std::uint32_t> records, const DatabaseAtlasStats& stats) {
    std::vector<std::uint8_t> tile;
    return record_atlas_of(db, records, stats, [&](std::size_t i) -> const std::vector<std::uint8_t>& {
        return tile = database_record_tiles(db, records[i], stats);
    });
}

RecordAtlas pack_record_atlas(const HrirDatabase& db) {
    std::vector<std::uint32_t> all(db.size());
    std::iota(all.begin(), all.end(), 0u);
    return pack_record_atlas(db, all, database_atlas_stats(db));
}

// The cache's contents: each kind's entries of the last cook that finished (`last`) and of the cook under way (`now`),
// which replace them when it finishes.
struct CookCache::State {
    struct Prototype {  // a prototype's stage 1
        std::uint64_t serial = 0;  // names its key in the clusters' keys (a key is the prototype's whole data)
        std::vector<ShellVertex> vertices;
        std::vector<std::uint32_t> indices;
        std::vector<MeshRange> meshes;  // first and base_vertex relative to the entry's arrays
        std::vector<ShellSector> sectors;
    };
    struct Cluster {  // a cluster's grid strands (the style's axes), their turned bounds, and its fibre-tilt sums
        Strands strands;
        std::size_t count = 0;  // ClusterStrandSampler::count
        glm::vec3 lo{std::numeric_limits<float>::max()}, hi{std::numeric_limits<float>::lowest()};
        FibreTiltSums tilts;
    };
    // Shared, not moved: a cook that throws leaves the last one's entries whole.
    std::map<std::string, std::shared_ptr<const Prototype>> prototypes_last, prototypes_now;
    std::map<std::string, std::shared_ptr<const Cluster>> clusters_last, clusters_now;
    std::map<std::uint32_t, std::shared_ptr<const std::vector<std::uint8_t>>> tiles_last, tiles_now;
    std::optional<GridSums> grid;  // the sums of clusters_last's strands, or none
    std::uint64_t next_serial = 1;
    std::vector<std::uint64_t> serial_of;  // this cook's: by style prototype index
    const HrirDatabase* stats_of = nullptr;
    DatabaseAtlasStats stats;
    Timings timings, now;

    void start() {
        prototypes_now.clear();
        clusters_now.clear();
        tiles_now.clear();
        serial_of.clear();
        now = Timings{};
    }
    void finish() {  // with grid already made of clusters_now's strands
        prototypes_last = std::move(prototypes_now);
        clusters_last = std::move(clusters_now);
        tiles_last = std::move(tiles_now);
        prototypes_now.clear();
        clusters_now.clear();
        tiles_now.clear();
        timings = now;
    }
};

CookCache::CookCache() : state_(std::make_unique<State>()) {}
CookCache::~CookCache() = default;
const CookCache::Timings& CookCache::timings() const { return state_->timings; }

const DatabaseAtlasStats& CookCache::atlas_stats(const HrirDatabase& db) {
    State& s = *state_;
    if (s.stats_of != &db) {
        s.stats = database_atlas_stats(db);
        s.stats_of = &db;
    }
    return s.stats;
}

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point& t) {
    const Clock::time_point now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - t).count();
    t = now;
    return ms;
}

void put_bytes(std::string& k, const void* p, std::size_t n) { k.append(static_cast<const char*>(p), n); }

// A prototype's cache key: its layout, shape and density, bit for bit.
std::string prototype_key(const DiskLayout& L, const Cluster& c) {
    std::string k;
    const auto put = [&](const void* p, std::size_t n) { put_bytes(k, p, n); };
    const int ints[] = {L.layers, L.s_t, L.s_u, L.grid_s, L.grid_r, L.mesh_t, L.mesh_u};
    put(ints, sizeof ints);
    put(&L.core_radius, sizeof(double));
    put(&L.gaussian_width, sizeof(double));
    const GeneralizedCylinder& g = *c.shape;
    const auto spline = [&](const std::vector<double>& v) {
        const std::size_t n = v.size();
        put(&n, sizeof n);
        put(v.data(), n * sizeof(double));
    };
    const std::size_t n = g.trajectory().size();
    put(&n, sizeof n);
    put(g.trajectory().control().data(), n * sizeof(glm::dvec3));
    spline(g.a_spline().control());
    spline(g.b_spline().control());
    spline(g.theta_spline().control());
    const DensitySource& d = *c.density;
    put(&d.kind, sizeof d.kind);
    put(&d.value, sizeof d.value);
    put(&d.strand_weight, sizeof d.strand_weight);
    for (const StrandRun& r : d.strands) {
        const std::size_t m = r.vu.size();
        put(&r.first_plane, sizeof r.first_plane);
        put(&m, sizeof m);
        put(r.vu.data(), m * sizeof(glm::dvec2));
    }
    k += '|';
    for (const std::vector<float>& grid : d.grids) {
        const std::size_t m = grid.size();
        put(&m, sizeof m);
        put(grid.data(), m * sizeof(float));
    }
    return k;
}

// A cluster's cache key: what its grid strands and fibre-tilt sums depend on besides its prototype (`serial`).
std::string cluster_key(std::uint64_t serial, std::size_t index, const Cluster& c, const glm::mat3& orientation,
                        int lighting_rows_per_hsv, const StrandSampling& sampling) {
    std::string k;
    put_bytes(k, &serial, sizeof serial);
    put_bytes(k, &index, sizeof index);
    put_bytes(k, &c.placement.scale, sizeof(double));
    put_bytes(k, &c.placement.rotation, sizeof(glm::dquat));
    put_bytes(k, &c.placement.translation, sizeof(glm::dvec3));
    put_bytes(k, &orientation, sizeof orientation);
    put_bytes(k, &lighting_rows_per_hsv, sizeof(int));
    put_bytes(k, &sampling.points_per_hsv, sizeof(int));
    put_bytes(k, &sampling.seed, sizeof sampling.seed);
    return k;
}

// The grid strands, the shadow grid and the fibre tilts of a cook with a cache (cook_shells): each cluster's strands
// and tilt sums taken from the last cook when its key is unchanged, the grid's sums updated by the clusters that changed.
// The same strands (in cluster order), grid and tilts as sampling, voxelizing and measuring them all.
void cached_strands_grid_tilts(CookCache::State& st, const HairStyle& style, PreparedShells& shells, const glm::mat3& orientation,
                               int lighting_rows_per_hsv, Strands& strands, std::vector<std::uint32_t>& strand_cluster,
                               DensityGrid& grid, float& tangent_spread) {
    const StrandSampling sampling{};
    ClusterStrandSampler sampler(style, sampling);
    auto t = Clock::now();
    std::vector<std::string> keys(style.clusters.size());
    std::vector<std::shared_ptr<const CookCache::State::Cluster>> kept(style.clusters.size());
    double total = 0;
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci) {
        keys[ci] = cluster_key(st.serial_of.at(style.clusters[ci].prototype), ci, style.clusters[ci], orientation,
                               lighting_rows_per_hsv, sampling);
        const auto it = st.clusters_last.find(keys[ci]);
        if (it != st.clusters_last.end()) kept[ci] = it->second;
        total += static_cast<double>(kept[ci] ? kept[ci]->count : sampler.count(ci));
    }
    if (total > sampling.max_strands) refuse_strand_count(total, sampling.max_strands);
    std::vector<std::shared_ptr<CookCache::State::Cluster>> made(style.clusters.size());
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci) {
        if (kept[ci]) continue;
        made[ci] = std::make_shared<CookCache::State::Cluster>();
        CookCache::State::Cluster& e = *made[ci];
        e.count = sampler.count(ci);
        e.strands = sampler.sample(ci);
        if (!e.strands.points.empty()) std::tie(e.lo, e.hi) = turned_bounds(e.strands, orientation);
        ++st.now.clusters_sampled;
    }
    st.now.strands_ms = ms_since(t);
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci)
        if (!kept[ci]) made[ci]->tilts = cluster_fibre_tilt_sums(shells, ci, made[ci]->strands, orientation);
    const auto entry = [&](std::size_t ci) -> const CookCache::State::Cluster& { return kept[ci] ? *kept[ci] : *made[ci]; };
    std::vector<FibreTiltSums> tilts;
    tilts.reserve(style.clusters.size());
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci) tilts.push_back(entry(ci).tilts);
    tangent_spread = set_fibre_tilts(shells, tilts);
    st.now.tilts_ms = ms_since(t);
    // The strands in cluster order.
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci) {
        strands.add_strands(entry(ci).strands);
        strand_cluster.resize(strands.strand_count(), static_cast<std::uint32_t>(ci));
    }
    if (strands.strand_count() == 0) strands.offsets.clear();
    strands.axes_stated = style_axes_stated(style);
    st.now.rest_ms += ms_since(t);
    // The grid: its frame is the bounds of every cluster's turned strands (as voxelize_strands takes them).
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci) {
        lo = glm::min(lo, entry(ci).lo);
        hi = glm::max(hi, entry(ci).hi);
    }
    // The sums are kept when the voxel size is (GridSums::can_reframe): framed to hold the old strands and the new,
    // the clusters that changed are taken out and put in, and the sums framed to the new bounds.
    const bool keep = st.grid && st.grid->can_reframe(lo, hi);
    std::optional<GridSums> fresh;
    if (!keep) fresh.emplace(lo, hi, kShadowGridSize);  // throws for no strands, before anything is changed
    // Nothing below throws (but for memory): the cache's grid becomes that of this cook's clusters.
    if (keep) {
        const glm::vec3 old_lo = st.grid->frame().strands_min, old_hi = st.grid->frame().strands_max;
        const bool moved = old_lo != lo || old_hi != hi;
        if (moved) st.grid->reframe(glm::min(lo, old_lo), glm::max(hi, old_hi));
        std::set<std::string> used;
        for (std::size_t ci = 0; ci < style.clusters.size(); ++ci)
            if (kept[ci]) used.insert(keys[ci]);
        for (const auto& [key, old] : st.clusters_last)
            if (!used.count(key)) st.grid->add(old->strands, orientation, -1);
        for (std::size_t ci = 0; ci < style.clusters.size(); ++ci)
            if (!kept[ci]) st.grid->add(made[ci]->strands, orientation, 1);
        if (moved) st.grid->reframe(lo, hi);
    } else {
        st.grid = std::move(fresh);
        st.grid->add(strands, orientation, 1);
        st.now.grid_rebuilt = true;
    }
    grid = st.grid->grid();
    st.now.grid_ms = ms_since(t);
    // The entries kept for the next cook.
    for (std::size_t ci = 0; ci < style.clusters.size(); ++ci)
        st.clusters_now.emplace(keys[ci], kept[ci] ? kept[ci] : std::shared_ptr<const CookCache::State::Cluster>(made[ci]));
    st.now.clusters = style.clusters.size();
    st.now.rest_ms += ms_since(t);
}

// Stage 1 (prepare_prototypes), with a cache's prototypes when given (a cook of cook_shells under way).
void prepare_prototypes_cached(PreparedShells& m, const HairStyle& style, const SatfIndex& satf, std::span<const float> mean_alpha,
                               CookCache::State* cache) {
    if (style.clusters.empty()) throw Error(style.name, "clusters", "the style has no clusters");
    m.layout = style.layout;
    m.prototypes.clear();
    std::vector<ShellVertex>& vertices = m.vertices.vector();
    std::vector<std::uint32_t>& indices = m.indices.vector();
    vertices.clear();
    indices.clear();
    m.triangles = 0;
    m.cluster_proto.assign(style.clusters.size(), SIZE_MAX);
    std::vector<std::size_t> slot_of(style.clusters.size(), SIZE_MAX);
    for (std::size_t c = 0; c < style.clusters.size(); ++c) {
        const std::size_t p = style.clusters[c].prototype;
        if (slot_of[p] == SIZE_MAX) {
            slot_of[p] = m.prototypes.size();
            m.prototypes.push_back(p);
        }
        m.cluster_proto[c] = slot_of[p];
    }
    if (cache) cache->serial_of.assign(style.clusters.size(), 0);
    const double lambda = m.layout.gaussian_width;
    // Each prototype's sectors, of its own layout (HairStyle::layout_of), one after another.
    std::vector<std::size_t> base(m.prototypes.size() + 1, 0);
    for (std::size_t p = 0; p < m.prototypes.size(); ++p) base[p + 1] = base[p] + style.layout_of(m.prototypes[p]).sector_count();
    m.sectors.assign(base.back(), ShellSector{});
    m.meshes.assign(m.prototypes.size(), {});
    for (std::size_t p = 0; p < m.prototypes.size(); ++p) {
        const Cluster& proto = style.clusters[m.prototypes[p]];
        const DiskLayout L = style.layout_of(m.prototypes[p]);
        const std::size_t per_proto = L.sector_count(), first_sector = base[p];
        const GeneralizedCylinder& shape = *proto.shape;
        std::string key;
        const std::size_t first_vertex = vertices.size(), first_index = indices.size();
        if (cache) {
            key = prototype_key(L, proto);
            const auto it = cache->prototypes_last.find(key);
            if (it != cache->prototypes_last.end()) {  // made by an earlier cook: the same arrays
                const CookCache::State::Prototype& e = *it->second;
                for (MeshRange r : e.meshes) {
                    r.first += static_cast<std::uint32_t>(first_index);
                    r.base_vertex += static_cast<std::int32_t>(first_vertex);
                    m.meshes[p].push_back(r);
                    m.triangles += static_cast<std::size_t>(r.count) / 3;
                }
                vertices.insert(vertices.end(), e.vertices.begin(), e.vertices.end());
                indices.insert(indices.end(), e.indices.begin(), e.indices.end());
                std::copy(e.sectors.begin(), e.sectors.end(), m.sectors.begin() + static_cast<std::ptrdiff_t>(first_sector));
                cache->serial_of[m.prototypes[p]] = e.serial;
                cache->prototypes_now.insert_or_assign(std::move(key), it->second);
                continue;
            }
        }
        for (int j = 0; j < L.layers; ++j) {
            const LayerMesh mesh = layer_mesh(shape, L, j);
            MeshRange range;
            range.first = static_cast<std::uint32_t>(indices.size());
            range.count = static_cast<std::int32_t>(mesh.indices.size());
            range.base_vertex = static_cast<std::int32_t>(vertices.size());
            range.vertex_count = static_cast<std::int32_t>(mesh.position.size());
            for (std::size_t v = 0; v < mesh.position.size(); ++v) {
                const Frame f = shape.frame(mesh.texcoord[v].y);
                vertices.push_back({mesh.position[v], mesh.tangent[v], mesh.normal[v], mesh.texcoord[v], glm::vec3(f.normal)});
            }
            indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
            m.meshes[p].push_back(range);
            m.triangles += mesh.indices.size() / 3;
        }
        const std::vector<float> rows = sector_feature_rows(cluster_sector_densities(shape, L, *proto.density), lambda);
        const std::vector<SectorMatch> matches = satf.match_all(rows);
        std::vector<float> sector_alpha(per_proto, 0.0f);
        for (std::size_t s = 0; s < per_proto; ++s) {
            ShellSector& sector = m.sectors[first_sector + s];
            sector = shell_sector(matches[s], mean_alpha, &sector_alpha[s]);
            const float c = sector_thinning(matches[s], rows[s * kRawFeatureCount + kMeanDensityColumn], satf.database());
            sector.shadow.z = c;
            sector_alpha[s] = thinned_alpha(sector_alpha[s], c);  // of the mean α: Σ ᾱ's units (eq. 12)
        }
        for (int i = 0; i <= L.s_t; ++i)
            for (int k = 0; k < L.s_u; ++k) {
                float outer = 0.0f;  // Σ ᾱ of the layers outside layer j (004 eq. 12's χ(k))
                for (int j = L.layers - 1; j >= 0; --j) {
                    const std::size_t s = L.sector_index(i, j, k);
                    m.sectors[first_sector + s].shadow.x = outer;
                    outer += sector_alpha[s];
                }
                for (int j = 0; j < L.layers; ++j)  // Σ ᾱ of every layer: one radius (shaders/lighting/own_cluster.glsl)
                    m.sectors[first_sector + L.sector_index(i, j, k)].shadow.y = outer;
            }
        if (cache) {
            auto e = std::make_shared<CookCache::State::Prototype>();
            e->serial = cache->next_serial++;
            e->vertices.assign(vertices.begin() + static_cast<std::ptrdiff_t>(first_vertex), vertices.end());
            e->indices.assign(indices.begin() + static_cast<std::ptrdiff_t>(first_index), indices.end());
            for (MeshRange r : m.meshes[p]) {
                r.first -= static_cast<std::uint32_t>(first_index);
                r.base_vertex -= static_cast<std::int32_t>(first_vertex);
                e->meshes.push_back(r);
            }
            e->sectors.assign(m.sectors.begin() + static_cast<std::ptrdiff_t>(first_sector),
                              m.sectors.begin() + static_cast<std::ptrdiff_t>(first_sector + per_proto));
            cache->serial_of[m.prototypes[p]] = e->serial;
            cache->prototypes_now.insert_or_assign(std::move(key), std::move(e));
            ++cache->now.prototypes_made;
        }
    }
    if (cache) cache->now.prototypes = m.prototypes.size();
}

// pack_record_atlas with the cache's tiles of the records it packed before.
RecordAtlas pack_record_atlas_cached(CookCache::State& st, const HrirDatabase& db, std::span<const std::uint32_t> records,
                                     const DatabaseAtlasStats& stats) {
    RecordAtlas a = record_atlas_of(db, records, stats, [&](std::size_t i) -> const std::vector<std::uint8_t>& {
        const std::uint32_t r = records[i];
        const auto it = st.tiles_last.find(r);
        std::shared_ptr<const std::vector<std::uint8_t>> tile;
        if (it != st.tiles_last.end()) tile = it->second;
        else {
            tile = std::make_shared<const std::vector<std::uint8_t>>(database_record_tiles(db, r, stats));
            ++st.now.records_packed;
        }
        return *st.tiles_now.insert_or_assign(r, std::move(tile)).first->second;
    });
    st.now.records = records.size();
    return a;
}

}  // namespace

void prepare_prototypes(PreparedShells& m, const HairStyle& style, const SatfIndex& satf, std::span<const float> mean_alpha) {
    prepare_prototypes_cached(m, style, satf, mean_alpha, nullptr);
}

PreparedShells prepare_shells(const HairStyle& style, const SatfIndex& satf, std::span<const float> mean_alpha,
                              const glm::mat3& orientation, int lighting_rows_per_hsv) {
    PreparedShells shells;
    prepare_prototypes(shells, style, satf, mean_alpha);
    place_clusters(shells, style, orientation, lighting_rows_per_hsv);
    return shells;
}

CookedShells cook_shells(const HairStyle& style, const SatfIndex& satf, const glm::mat3& orientation,
                         int lighting_rows_per_hsv, Strands* sampled_strands, CookCache* cache) {
    const HrirDatabase& db = satf.database();
    if (style.clusters.empty()) throw Error(style.name, "clusters", "the style has no clusters");
    const auto started = Clock::now();
    auto t = started;
    CookCache::State* st = cache ? &cache->state() : nullptr;
    if (st) st->start();
    CookedShells c;
    c.name = style.name;
    c.source = c.database = db.path().string();
    c.database_records = db.size();
    const DatabaseAtlasStats local = cache ? DatabaseAtlasStats{} : database_atlas_stats(db);
    const DatabaseAtlasStats& stats = cache ? cache->atlas_stats(db) : local;
    prepare_prototypes_cached(c.shells, style, satf, stats.mean_alpha, st);
    place_clusters(c.shells, style, orientation, lighting_rows_per_hsv);
    if (st) st->now.prototypes_ms = ms_since(t);
    // Only the records the sectors use go into the atlas, renumbered in order of their database id.
    std::vector<std::uint32_t> used;
    for (const ShellSector& s : c.shells.sectors)
        for (int n = 0; n < gl::kMaxShellNeighbours; ++n) used.push_back(s.id[n]);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    for (ShellSector& s : c.shells.sectors)
        for (int n = 0; n < gl::kMaxShellNeighbours; ++n)
            s.id[n] = static_cast<std::uint32_t>(std::lower_bound(used.begin(), used.end(), s.id[n]) - used.begin());
    c.atlas = st ? pack_record_atlas_cached(*st, db, used, stats) : pack_record_atlas(db, used, stats);
    if (st) st->now.atlas_ms = ms_since(t);
    // The shadow grid (decision 5): the strands the reference renderer draws, voxelized; and how the same strands'
    // tangents tilt about each lighting sample's, for the lighting.
    std::vector<std::uint32_t> strand_cluster;
    Strands strands;
    if (st) {
        cached_strands_grid_tilts(*st, style, c.shells, orientation, lighting_rows_per_hsv, strands, strand_cluster, c.grid,
                                  c.tangent_spread);
        st->finish();  // the cache's grid is this cook's now: so are its entries
        t = Clock::now();
    } else {
        strands = sample_strands(style, StrandSampling{}, &strand_cluster);
        c.grid = voxelize_strands(strands, orientation, kShadowGridSize);
        c.tangent_spread = measure_fibre_tilts(c.shells, strands, strand_cluster, orientation);
    }
    // coif reference's radius is of the strands as it draws them: turned, as the grid holds them.
    c.auto_fiber_radius = static_cast<float>(auto_fiber_radius(glm::dvec3(c.grid.strands_min), glm::dvec3(c.grid.strands_max)));
    c.shadow_strands = strands.strand_count();
    // The box a camera frames (hair_scene.h SceneFraming): the strands turned y-up, as coif reference frames them.
    const StrandStats sst = strand_stats(oriented_y_up(strands));
    c.frame_min = glm::vec3(sst.bbox_min);
    c.frame_max = glm::vec3(sst.bbox_max);
    // What moving the clusters needs: their roots, the grid's strands turned as the grid holds them, the bone weights.
    c.body_orientation = orientation * style_source_rotation(style);
    c.roots = cluster_roots(style, orientation);
    std::vector<glm::vec3>& points = c.shadow_source.points.vector();
    points.reserve(strands.points.size());
    for (const glm::vec3& q : strands.points) points.push_back(orientation * q);
    c.shadow_source.offsets = strands.offsets;
    c.shadow_strand_cluster = std::move(strand_cluster);
    c.skinning = style.skinning;
    if (sampled_strands) *sampled_strands = std::move(strands);
    if (st) {
        st->timings.rest_ms += ms_since(t);
        st->timings.total_ms = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
    }
    return c;
}

}  // namespace coif
