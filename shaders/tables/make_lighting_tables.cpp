// Build step: computes the parameter-free lighting tables (shaders/lighting_tables.h build_lighting_tables) and
// writes them in the form lighting_tables_from_bytes reads, so that coif::shading embeds them instead of computing
// them in every process (≈ 0.5 s on 2 cores). Compiled with the shading sources and COIF_LIGHTING_TABLES_GENERATOR,
// so that it computes rather than reading the tables it is making.
//   coif_make_lighting_tables OUT
#include <cstdio>
#include <fstream>

#include "shaders/lighting_tables.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: coif_make_lighting_tables OUT\n");
        return 2;
    }
    const std::vector<std::byte> bytes = coif::shading::lighting_tables_bytes(coif::shading::build_lighting_tables());
    std::ofstream out(argv[1], std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return out ? 0 : 1;
}
