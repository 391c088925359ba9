#pragma once
// The default HRIR database: what a renderer uses when given no database file. It is built once, on first
// use, into the user's cache folder ($XDG_CACHE_HOME/coif, else ~/.cache/coif) and reused afterwards; its
// file name carries its build parameters' hash, so a change of the default parameters builds a new one.
#include <cstdint>
#include <filesystem>
#include <iosfwd>

#include "db/hrir_db.h"

namespace coif {

// Sectors of the default database (docs/db.md: 1000 sectors, about 2 minutes on 2 cores).
inline constexpr std::uint64_t kDefaultDatabaseSectors = 1000;

// <cache>/coif/default-<sectors>-<params hash>.db, cache = $XDG_CACHE_HOME, else ~/.cache, else the temporary
// folder.
std::filesystem::path default_database_path();

// `path` when not empty, else the default database, built (with every core) when missing. Which one is used,
// and that a build starts, goes to `log` (one line each; nullptr: nothing is said).
HrirDatabase open_database_or_default(const std::filesystem::path& path, std::ostream* log);

}  // namespace coif
