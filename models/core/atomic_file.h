#pragma once
// Atomic writes: every file coif writes is first written to a temporary file in the same folder
// ("<name>.tmp-<pid>-<n><ext>", keeping the extension so format-sniffing writers still work) and then
// renamed over the destination. On any failure the temporary is removed: a failed write never leaves
// a partial or half-updated file behind.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

namespace coif {

// Calls write(temp_path) and renames temp_path to path when it returns normally; removes the
// temporary and rethrows when it throws. Throws coif::Error if the folder is missing or the rename fails.
void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

// Writes bytes to path atomically.
void write_file_atomic(const std::filesystem::path& path, std::span<const std::byte> bytes);
void write_file_atomic(const std::filesystem::path& path, std::string_view text);

// Reads a whole file; throws coif::Error naming the file if it cannot.
std::vector<std::byte> read_file_bytes(const std::filesystem::path& path);

}  // namespace coif
