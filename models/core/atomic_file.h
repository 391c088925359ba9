#pragma once
// Atomic writes: every file coif writes is first written to a temporary file in the same folder
// ("<stem>.tmp-<pid>-<n><ext>", keeping the extension so format-sniffing writers still work), flushed to
// the disk (fsync), renamed over the destination, and the folder is flushed too, so that a power loss
// leaves either the old file or the whole new one, never a renamed but empty one. On any failure (a full
// disk, a read-only folder, a writer that throws) the temporary is removed and a coif::Error names the
// destination: a failed write never leaves a partial or half-updated file behind. A process killed in the
// middle leaves its temporary; the next run that locks the same output (OutputLock) removes it.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace coif {

// Calls write(temp_path), flushes the temporary to the disk and renames it to path when write returns
// normally; removes the temporary and rethrows when it throws. Throws coif::Error if the folder is
// missing, or the flush or the rename fails.
void write_atomically(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

// Writes bytes to path atomically.
void write_file_atomic(const std::filesystem::path& path, std::span<const std::byte> bytes);
void write_file_atomic(const std::filesystem::path& path, std::string_view text);

// Reads a whole file; throws coif::Error naming the file if it cannot.
std::vector<std::byte> read_file_bytes(const std::filesystem::path& path);

// The advisory lock (flock(2)) on writing `path`, held while the object lives: a second process asking for
// it gets, at once, a coif::Error naming the file and the process that holds it. Holders within one
// process share the lock (a command locks its output, and the library function it calls locks it again).
// The lock file is "<path>.lock" beside the output, removed when the last holder lets go; one left by a
// killed process is simply taken over (the kernel released its lock). Taking the lock also removes the
// temporaries of `path` that a killed writer left (remove_stale_temporaries).
//
// flock stops processes on one machine. On a shared filesystem (NFS and the like) it may not stop two
// machines: there, give each job its own output (each shard of `coif db build --shard i/n` its own file,
// joined by `coif db merge`).
class OutputLock {
public:
    explicit OutputLock(const std::filesystem::path& path);
    const std::filesystem::path& path() const { return path_; }
    static std::filesystem::path lock_file(const std::filesystem::path& path);  // "<path>.lock"

private:
    std::filesystem::path path_;
    std::shared_ptr<const void> held_;
};

// An exclusive advisory lock (flock(2)) on the file `lock_file` (created if missing), held while the object lives:
// unlike OutputLock, a second process asking for it waits until the first lets go. For work that every process would
// do alike, such as building a cache file: the first does it, the others then find it done. `before_waiting` is
// called when another process holds the lock, before this one waits for it (to say so).
class WaitingLock {
public:
    explicit WaitingLock(const std::filesystem::path& lock_file, const std::function<void()>& before_waiting = {});
    ~WaitingLock();
    WaitingLock(const WaitingLock&) = delete;
    WaitingLock& operator=(const WaitingLock&) = delete;

private:
    int fd_ = -1;
};

// Removes the temporaries of `path` ("<stem>.tmp-<pid>-<n><ext>" in its folder) whose writing process is
// no longer running; returns how many. Temporaries of live processes are left alone.
std::size_t remove_stale_temporaries(const std::filesystem::path& path);
// The same for every coif temporary in `folder` (the chunk folder of a resumable build).
std::size_t remove_stale_temporaries_in(const std::filesystem::path& folder);

}  // namespace coif
