#pragma once
// `coif` running itself as a subprocess, for the benchmarks that drive whole commands (coif bench quality, coif bench
// sweep): each run is what a user would type, with its output in a log file.
#include <filesystem>
#include <string>

namespace coif::cli {

// `s` in single quotes for /bin/sh, its own single quotes escaped.
std::string shell_quote(const std::string& s);

// The whole text of a file ("" when it cannot be read).
std::string read_text(const std::filesystem::path& path);

// The wall and CPU seconds of one run (the CPU of the child processes).
struct RunTimes {
    double wall = 0, cpu = 0;
};

// Runs `coif <args>` (this executable), stdout and stderr into `log`; throws coif::Error with the tail of the log when
// the command fails.
RunTimes run_self(const std::string& args, const std::filesystem::path& log);

// The folder a benchmark works in: `keep` when given (created; kept), else a new temporary folder named `prefix` and the
// process id, removed with this object. Throws coif::Error naming the folder when it cannot be made.
class WorkFolder {
public:
    WorkFolder(const std::string& keep, const std::string& prefix);
    ~WorkFolder();
    WorkFolder(const WorkFolder&) = delete;
    WorkFolder& operator=(const WorkFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }
    bool temporary() const { return temporary_; }

private:
    std::filesystem::path path_;
    bool temporary_;
};

}  // namespace coif::cli
