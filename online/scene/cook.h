#pragma once
// Cooking: a hairstyle and an HRIR database become the CookedShells that the shell renderer draws
// (online/shells/hair_asset.h), GL-free. This is the half of the renderer's preparation that needs the
// database and its FLANN index (db/): the sectors' look-ups, and the records they use packed into an atlas.
// `coif render STYLE` cooks on every load; `coif bake` cooks once and writes the result as a `.coif` asset,
// which the runtime (coif::runtime) loads without the database.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "db/hrir_db.h"
#include "db/satf.h"
#include "models/hair_style.h"
#include "models/strands.h"
#include "online/shells/hair_asset.h"

namespace coif {


// What the atlas of any subset of a database's records needs from all of them: the quantisation ranges of the 12
// channels (online/shells/record_atlas.h), each record's mean α and mean re a0, and re_norm. One pass over the
// records.
struct DatabaseAtlasStats {
    std::array<glm::vec4, kAtlasParts> lo{}, scale{};
    std::vector<float> mean_alpha, mean_a0;
    float re_norm = 1;
};
DatabaseAtlasStats database_atlas_stats(const HrirDatabase& db);

// The atlas of `records` (database record ids; the atlas's record i is records[i]) with the database-wide ranges
// and re_norm of `stats`, so that its texels are those of the whole database's atlas.
RecordAtlas pack_record_atlas(const HrirDatabase& db, std::span<const std::uint32_t> records, const DatabaseAtlasStats& stats);
// Every record of the database, in order.
RecordAtlas pack_record_atlas(const HrirDatabase& db);

// What a cook made, kept for the next cook of the same style being edited (coif view's cluster authoring), so that an
// edit of a few clusters makes only what they change and the result is the same, bit for bit, as a cook from nothing:
//   - each prototype's layer meshes, sector look-ups and shadow sums, keyed by its layout, shape and density bit for bit;
//   - each cluster's grid strands (models/style_strands.h ClusterStrandSampler) and fibre-tilt sums
//     (prepared_shells.h FibreTiltSums), keyed by its prototype's key, its placement, its index (its strands' seed),
//     the orientation and the lighting rows;
//   - the shadow grid's fixed-point sums (shadow_grid.h GridSums): a changed cluster's old strands are taken out and its
//     new ones put in, unless the strands' bounds changed the voxel size (GridSums::can_reframe), when all are voxelized again;
//   - each used record's atlas tiles (record_atlas.h record_tiles), by record id;
//   - the database's atlas ranges (database_atlas_stats).
// It holds what the last cook that finished used, and nothing of a cook that threw. For one database: a cache must not
// outlive its SatfIndex or serve another.
class CookCache {
public:
    CookCache();
    ~CookCache();
    CookCache(const CookCache&) = delete;
    CookCache& operator=(const CookCache&) = delete;

    // Of the last cook that finished: what it made anew and the wall-clock time of each part.
    struct Timings {
        double total_ms = 0;
        double prototypes_ms = 0;  // meshes, sector densities, look-ups (prepare_prototypes) and placement
        double atlas_ms = 0;       // the used records' atlas
        double strands_ms = 0;     // sampling the grid's strands
        double tilts_ms = 0;       // the fibre-tilt sums
        double grid_ms = 0;        // the shadow grid
        double rest_ms = 0;        // joining the strands, framing, the moving data
        std::size_t prototypes = 0, prototypes_made = 0;
        std::size_t clusters = 0, clusters_sampled = 0;
        std::size_t records = 0, records_packed = 0;
        bool grid_rebuilt = false;  // voxelized from all strands (the first cook, or the strands' bounds changed)
    };
    const Timings& timings() const;
    // The database's atlas ranges, computed on first use and kept: they depend on the database alone.
    const DatabaseAtlasStats& atlas_stats(const HrirDatabase& db);

    struct State;  // online/scene/cook.cpp
    State& state() { return *state_; }

private:
    std::unique_ptr<State> state_;
};

// A sector's thinning of its records (ShellSector::shadow.z): its mean density ρ̄ over the match's records' (weighted as
// the match weighs them; models/sector_features.h kMeanDensityColumn), at most 1, and 1 where the records have no
// density. Sparse sectors match records of denser ones; the shells draw those thinned to the sector's own density
// (shaders/gl/record_atlas.glsl thinned_alpha), which brings the hair's coverage and level to the strands' under single
// lights (docs/quality.md, "The records thinned to their sectors' density").
float sector_thinning(const SectorMatch& match, double sector_density, const HrirDatabase& db);

// Stage 1 of the preparation (online/shells/prepared_shells.h): meshes, sector look-ups, their thinning
// (sector_thinning) and the thinned shadow sums of every prototype. `mean_alpha`: per database record. Sector ids are
// database record ids. Throws coif::Error if the style has no clusters.
void prepare_prototypes(PreparedShells& shells, const HairStyle& style, const SatfIndex& satf,
                        std::span<const float> mean_alpha);
// Stages 1 and 2.
PreparedShells prepare_shells(const HairStyle& style, const SatfIndex& satf, std::span<const float> mean_alpha,
                              const glm::mat3& orientation, int lighting_rows_per_hsv = 0);

// Everything the shell renderer draws a style with: both stages, the records the sectors use (and only those)
// packed with the database's ranges, with the sectors' ids renumbered to them, the shadow grid of the style's
// strands (models/style_strands.h, StrandSampling{}), the fibres' tilts and the auto fibre radius.
// `lighting_rows_per_hsv` as place_clusters. `sampled_strands`, if given, receives the sampled strands (the style's
// axes, not turned), so that a caller need not sample again. `cache`: see CookCache (null: everything made). Throws
// coif::Error as the stages do.
CookedShells cook_shells(const HairStyle& style, const SatfIndex& satf, const glm::mat3& orientation,
                         int lighting_rows_per_hsv = 0, Strands* sampled_strands = nullptr, CookCache* cache = nullptr);

}  // namespace coif
