#pragma once
// Cooking: a hairstyle and an HRIR database become the CookedShells that the shell renderer draws
// (online/shells/hair_asset.h), GL-free. This is the half of the renderer's preparation that needs the
// database and its FLANN index (db/): the sectors' look-ups, and the records they use packed into an atlas.
// `coif render STYLE` cooks on every load; `coif bake` cooks once and writes the result as a `.coif` asset,
// which the runtime (coif::runtime) loads without the database.
#include <array>
#include <map>
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

// What stage 1 made of each prototype (its layer meshes, its sectors' look-ups and shadow sums), kept between cooks
// of a style being edited (coif view's cluster authoring): a prototype whose shape, density and layout are unchanged,
// bit for bit, is taken from here instead of being made again, and the result is the same. Its entries are keyed by
// those contents; it holds the prototypes of the last cook only. For one database: a cache must not outlive its
// SatfIndex or serve another.
class PrototypeCache {
public:
    struct Entry {
        std::vector<ShellVertex> vertices;
        std::vector<std::uint32_t> indices;
        std::vector<MeshRange> meshes;  // first and base_vertex relative to the entry's arrays
        std::vector<ShellSector> sectors;
    };
    std::size_t hits() const { return hits_; }      // of the last cook
    std::size_t misses() const { return misses_; }
    // The database's atlas ranges (database_atlas_stats), computed on the first cook and kept: they depend on the
    // database alone.
    const DatabaseAtlasStats& atlas_stats(const HrirDatabase& db);
    // Internal to prepare_prototypes.
    const Entry* find(const std::string& key);
    void keep(std::string key, Entry entry);
    void start();  // a cook begins: the last one's entries become the ones it may take from

private:
    std::map<std::string, Entry> last_, now_;
    std::size_t hits_ = 0, misses_ = 0;
    const HrirDatabase* stats_of_ = nullptr;
    DatabaseAtlasStats stats_;
};

// Stage 1 of the preparation (online/shells/prepared_shells.h): meshes, sector look-ups and shadow sums of every
// prototype. `mean_alpha`: per database record. Sector ids are database record ids. Throws coif::Error if the
// style has no clusters. `cache`: see PrototypeCache (null: every prototype made).
void prepare_prototypes(PreparedShells& shells, const HairStyle& style, const SatfIndex& satf,
                        std::span<const float> mean_alpha, PrototypeCache* cache = nullptr);
// Stages 1 and 2.
PreparedShells prepare_shells(const HairStyle& style, const SatfIndex& satf, std::span<const float> mean_alpha,
                              const glm::mat3& orientation, int lighting_rows_per_hsv = 0, PrototypeCache* cache = nullptr);

// Everything the shell renderer draws a style with: both stages, the records the sectors use (and only those)
// packed with the database's ranges, with the sectors' ids renumbered to them, the shadow grid of the style's
// strands (models/style_strands.h, StrandSampling{}), the fibres' tilts and the auto fibre radius.
// `lighting_rows_per_hsv` as place_clusters. `sampled_strands`, if given, receives the sampled strands (the style's
// axes, not turned), so that a caller need not sample again. Throws coif::Error as the stages do.
CookedShells cook_shells(const HairStyle& style, const SatfIndex& satf, const glm::mat3& orientation,
                         int lighting_rows_per_hsv = 0, Strands* sampled_strands = nullptr, PrototypeCache* cache = nullptr);

}  // namespace coif
