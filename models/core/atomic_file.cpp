#include "models/core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <unistd.h>

#include "models/core/error.h"

namespace coif {
namespace fs = std::filesystem;

namespace {
fs::path temp_path_for(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    fs::path temp = path;
    temp.replace_filename(path.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                          std::to_string(counter++) + path.extension().string());
    return temp;
}
}  // namespace

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(parent, ec))
        throw Error(path, "", "cannot write: folder '" + parent.string() + "' does not exist");
    if (fs::is_directory(path, ec)) throw Error(path, "", "cannot write: it is a folder");
    const fs::path temp = temp_path_for(path);
    try {
        write(temp);
    } catch (...) {
        fs::remove(temp, ec);
        throw;
    }
    fs::rename(temp, path, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw Error(path, "", "cannot move the finished temporary file into place: " + ec.message());
    }
}

void write_file_atomic(const fs::path& path, std::span<const std::byte> bytes) {
    write_atomically(path, [&](const fs::path& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(path, "", std::string("cannot open for writing: ") + std::strerror(errno));
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        out.flush();
        if (!out) throw Error(path, "", "write failed (disk full?)");
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

}  // namespace coif
