#include "tools/subprocess.h"

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "models/core/error.h"

namespace coif::cli {
namespace fs = std::filesystem;

std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string read_text(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

namespace {

std::string self_exe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw Error::parameter("coif", "cannot find the coif executable (/proc/self/exe)");
    // A coif rebuilt while it runs reads as "PATH (deleted)": the new one at PATH runs the rest.
    std::string path = p.string();
    const std::string deleted = " (deleted)";
    if (path.size() > deleted.size() && path.compare(path.size() - deleted.size(), deleted.size(), deleted) == 0)
        path.resize(path.size() - deleted.size());
    return path;
}

double children_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_CHILDREN, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

RunTimes run_self(const std::string& args, const fs::path& log) {
    const double cpu0 = children_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    const std::string cmd = shell_quote(self_exe()) + " " + args + " >" + shell_quote(log.string()) + " 2>&1";
    const int status = std::system(cmd.c_str());
    RunTimes t;
    t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    t.cpu = children_cpu_seconds() - cpu0;
    if (status != 0) {
        std::string text = read_text(log);
        if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
        throw Error(log, "command `coif " + args + "`", "failed:\n" + text);
    }
    return t;
}

WorkFolder::WorkFolder(const std::string& keep, const std::string& prefix) : temporary_(keep.empty()) {
    path_ = temporary_ ? fs::temp_directory_path() / (prefix + std::to_string(::getpid())) : fs::path(keep);
    std::error_code ec;
    fs::create_directories(path_, ec);
    if (!fs::is_directory(path_)) throw Error(path_, temporary_ ? "temporary folder" : "option --keep", "cannot create this folder");
}

WorkFolder::~WorkFolder() {
    std::error_code ec;
    if (temporary_) fs::remove_all(path_, ec);
}

}  // namespace coif::cli
