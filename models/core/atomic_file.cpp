#include "models/core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <mutex>
#include <signal.h>
#include <string>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "models/core/error.h"

namespace coif {
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kTempTag = ".tmp-";

fs::path temp_path_for(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path temp = path;
    temp.replace_filename(path.stem().string() + std::string(kTempTag) + std::to_string(::getpid()) + "-" +
                          std::to_string(counter++) + path.extension().string());
    return temp;
}

fs::path folder_of(const fs::path& path) { return path.has_parent_path() ? path.parent_path() : fs::path("."); }

// The folder `path` goes into; throws if it does not exist (before anything is created there).
fs::path existing_folder_of(const fs::path& path) {
    const fs::path parent = folder_of(path);
    std::error_code ec;
    if (!fs::is_directory(parent, ec)) throw Error(path, "", "cannot write: folder '" + parent.string() + "' does not exist");
    return parent;
}

std::string errno_text(int e) { return std::strerror(e); }

Error write_failed(const fs::path& path, int e) {
    return Error(path, "", "write failed: " + errno_text(e) + (e == ENOSPC ? " (the disk is full)" : ""));
}

// Flushes a written file to the disk. A full disk can surface only here (delayed allocation), so this is
// where the write is known to have succeeded.
void sync_file(const fs::path& file, const fs::path& named) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(named, "", "cannot reopen the written temporary file: " + errno_text(errno));
    if (::fsync(fd) != 0) {
        const int e = errno;
        ::close(fd);
        throw write_failed(named, e);
    }
    ::close(fd);
}

// Flushes the folder's entry for a renamed file. EINVAL: the filesystem cannot sync folders (nothing to do).
void sync_folder(const fs::path& folder, const fs::path& named) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) throw Error(named, "", "written, but its folder cannot be opened to flush it: " + errno_text(errno));
    if (::fsync(fd) != 0 && errno != EINVAL) {
        const int e = errno;
        ::close(fd);
        throw Error(named, "", "written, but flushing its folder failed: " + errno_text(e));
    }
    ::close(fd);
}

// A coif temporary "<stem>.tmp-<pid>-<n><ext>" (temp_path_for): its writer's pid and the file name it will
// be renamed to ("<stem><ext>"); pid 0 for any other name.
struct Temporary {
    pid_t pid = 0;
    std::string output;
};

Temporary parse_temporary(const std::string& name) {
    const std::size_t at = name.rfind(kTempTag);
    if (at == std::string::npos) return {};
    std::size_t i = at + kTempTag.size();
    const auto digits = [&] {
        const std::size_t from = i;
        while (i < name.size() && name[i] >= '0' && name[i] <= '9') ++i;
        return i - from;
    };
    const std::size_t pid_begin = i, pid_digits = digits();
    if (pid_digits == 0 || pid_digits > 9 || i >= name.size() || name[i] != '-') return {};
    ++i;
    if (digits() == 0 || (i < name.size() && name[i] != '.')) return {};
    return {static_cast<pid_t>(std::stol(name.substr(pid_begin, pid_digits))), name.substr(0, at) + name.substr(i)};
}

bool process_running(pid_t pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

// Removes the temporaries in `folder` whose output `belongs` accepts and whose writer is gone.
template <class Belongs>
std::size_t remove_stale(const fs::path& folder, Belongs&& belongs) {
    std::error_code ec;
    std::size_t removed = 0;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const Temporary t = parse_temporary(it->path().filename().string());
        if (t.pid <= 0 || !belongs(t.output) || process_running(t.pid)) continue;
        std::error_code rm;
        if (fs::remove(it->path(), rm)) ++removed;
    }
    return removed;
}

// One lock per output and process: the open, flock'ed lock file. A forked child inherits the registry but
// not the lock's ownership: it neither shares the parent's lock nor removes its file.
struct HeldLock {
    fs::path lock_file;
    int fd = -1;
    pid_t owner = ::getpid();
    ~HeldLock() {
        if (owner != ::getpid()) return;
        ::unlink(lock_file.c_str());  // before close: whoever opens it next finds it gone and starts over
        ::close(fd);
    }
};

std::mutex held_mutex;
std::map<fs::path, std::weak_ptr<HeldLock>> held_locks;  // by absolute output path

std::string holder_of(int fd) {
    char text[32] = {};
    const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
    if (n <= 0) return "";
    std::string pid(text, static_cast<std::size_t>(n));
    while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
    return pid.find_first_not_of("0123456789") == std::string::npos && !pid.empty() ? " (pid " + pid + ")" : "";
}

std::shared_ptr<HeldLock> take_lock(const fs::path& path) {
    const fs::path lock = OutputLock::lock_file(path);
    for (int attempt = 0; attempt < 16; ++attempt) {
        const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
        if (fd < 0)
            throw Error(path, "", "cannot write here: creating the lock file '" + lock.string() + "' failed: " + errno_text(errno));
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int e = errno;
            const std::string holder = holder_of(fd);
            ::close(fd);
            if (e == EWOULDBLOCK)
                throw Error(path, "", "another process" + holder + " is writing this file (it holds '" + lock.string() +
                                          "'); wait for it to finish, or write to another file");
            throw Error(path, "", "cannot lock '" + lock.string() + "': " + errno_text(e));
        }
        // The lock is ours if the file we locked is still the one at the path (its last holder may have
        // removed it between our open and our flock).
        struct stat locked {}, named {};
        if (::fstat(fd, &locked) == 0 && ::stat(lock.c_str(), &named) == 0 && locked.st_ino == named.st_ino &&
            locked.st_dev == named.st_dev) {
            const std::string pid = std::to_string(::getpid()) + "\n";
            if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
                const int e = errno;
                ::unlink(lock.c_str());
                ::close(fd);
                throw Error(path, "", "cannot write the lock file '" + lock.string() + "': " + errno_text(e));
            }
            auto held = std::make_shared<HeldLock>();
            held->lock_file = lock;
            held->fd = fd;
            return held;
        }
        ::close(fd);
    }
    throw Error(path, "", "cannot lock '" + lock.string() + "': other processes keep replacing it");
}

}  // namespace

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    const fs::path parent = existing_folder_of(path);
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw Error(path, "", "cannot write: it is a folder");
    const fs::path temp = temp_path_for(path);
    try {
        write(temp);
        sync_file(temp, path);
    } catch (...) {
        fs::remove(temp, ec);
        throw;
    }
    fs::rename(temp, path, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw Error(path, "", "cannot move the finished temporary file into place: " + ec.message());
    }
    sync_folder(parent, path);
}

void write_file_atomic(const fs::path& path, std::span<const std::byte> bytes) {
    write_atomically(path, [&](const fs::path& temp) {
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd < 0) throw Error(path, "", "cannot open for writing: " + errno_text(errno));
        std::size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                const int e = n < 0 ? errno : EIO;
                ::close(fd);
                throw write_failed(path, e);
            }
            done += static_cast<std::size_t>(n);
        }
        if (::close(fd) != 0) throw write_failed(path, errno);
    });
}

void write_file_atomic(const fs::path& path, std::string_view text) {
    write_file_atomic(path, std::as_bytes(std::span(text.data(), text.size())));
}

std::vector<std::byte> read_file_bytes(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(path, "", "no such file");
    if (fs::is_directory(path, ec)) throw Error(path, "", "is a folder, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "", std::string("cannot open: ") + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) throw Error(path, "", "cannot determine the file size");
    in.seekg(0);
    std::vector<std::byte> bytes(static_cast<size_t>(size));
    in.read(reinterpret_cast<char*>(bytes.data()), size);
    if (!in) throw Error(path, "", "read failed");
    return bytes;
}

WaitingLock::WaitingLock(const fs::path& lock_file, const std::function<void()>& before_waiting) {
    fd_ = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd_ < 0) throw Error(lock_file, "", "cannot create this lock file: " + errno_text(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
    if (before_waiting) before_waiting();
    while (::flock(fd_, LOCK_EX) != 0) {
        const int e = errno;
        if (e == EINTR) continue;
        ::close(fd_);
        throw Error(lock_file, "", "cannot lock this file: " + errno_text(e));
    }
}

WaitingLock::~WaitingLock() { ::close(fd_); }  // closing releases the flock

fs::path OutputLock::lock_file(const fs::path& path) {
    fs::path lock = path;
    lock += ".lock";
    return lock;
}

OutputLock::OutputLock(const fs::path& path) : path_(path) {
    existing_folder_of(path);
    std::error_code ec;
    const fs::path key = fs::absolute(path, ec).lexically_normal();
    std::lock_guard guard(held_mutex);
    std::weak_ptr<HeldLock>& slot = held_locks[ec ? path : key];
    std::shared_ptr<HeldLock> held = slot.lock();
    if (!held || held->owner != ::getpid()) {
        held = take_lock(path);
        slot = held;
        remove_stale_temporaries(path);
    }
    held_ = std::move(held);
}

std::size_t remove_stale_temporaries(const fs::path& path) {
    const std::string output = path.filename().string();
    return remove_stale(folder_of(path), [&](const std::string& of) { return of == output; });
}

std::size_t remove_stale_temporaries_in(const fs::path& folder) {
    return remove_stale(folder, [](const std::string&) { return true; });
}

}  // namespace coif
