#include "db/default_database.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>

#include "models/core/atomic_file.h"
#include "models/core/parallel.h"

namespace coif {

std::filesystem::path default_database_path() {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    const std::filesystem::path base = xdg && *xdg ? std::filesystem::path(xdg)
                                     : home && *home ? std::filesystem::path(home) / ".cache"
                                                     : std::filesystem::temp_directory_path();
    DbParams p;
    p.sectors = kDefaultDatabaseSectors;
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(params_hash(p)));
    return base / "coif" / ("default-" + std::to_string(p.sectors) + "-" + hash + ".db");
}

HrirDatabase open_database_or_default(const std::filesystem::path& path, std::ostream* log) {
    if (!path.empty()) return HrirDatabase::open(path);
    const std::filesystem::path cached = default_database_path();
    if (std::filesystem::exists(cached)) {
        if (log) *log << "coif: no --db given: using the cached default database " << cached.string() << "\n" << std::flush;
        return HrirDatabase::open(cached);
    }
    std::filesystem::create_directories(cached.parent_path());
    // Processes that want the default database at once (tests run in parallel, two commands started together) take
    // turns: the first builds it while holding this lock, the others wait for it and open what it built, rather than
    // stopping at the output's own lock (atomic_file.h OutputLock) as a second writer of one file does.
    const WaitingLock turn(cached.string() + ".building", [log] {
        if (log) *log << "coif: another process is building the default database; waiting for it\n" << std::flush;
    });
    if (std::filesystem::exists(cached)) {
        if (log) *log << "coif: no --db given: using the default database another process built, " << cached.string() << "\n"
                      << std::flush;
        return HrirDatabase::open(cached);
    }
    BuildOptions b;
    b.params.sectors = kDefaultDatabaseSectors;
    b.threads = thread_count(0);  // every hardware thread
    if (log)
        *log << "coif: no --db given: building the default database (" << b.params.sectors << " sectors, " << b.threads
             << " threads) into " << cached.string() << "; later runs reuse it\n"
             << std::flush;
    build_database(b, cached);
    return HrirDatabase::open(cached);
}

}  // namespace coif
