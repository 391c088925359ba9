#pragma once
// Files of tools/assets/ compiled into the coif binary (the embedded default scene), by path
// relative to tools/assets/, e.g. "default_strands.hair". See tools/assets/PROVENANCE.md.
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace coif::embedded {
std::optional<std::span<const unsigned char>> asset(std::string_view path);
}

namespace coif {
// The asset's bytes; throws coif::Error if it is not compiled in.
std::vector<std::byte> asset_bytes(std::string_view path);
}
