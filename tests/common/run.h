#pragma once
// Runs the coif executable built with the tests and captures its exit code, stdout and stderr.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "tests/common/test_data.h"

namespace coif::test {

struct RunResult {
    int exit_code = -1;
    std::string out, err;
};

inline std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// `args` is appended to the coif path as shell text (quote paths with spaces yourself); `prefix`, if given, is
// put before it (e.g. xvfb-run for a window).
inline RunResult run_coif(const std::string& args, const std::string& prefix = "") {
    static int counter = 0;
    const auto dir = std::filesystem::temp_directory_path();
    const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const auto out = dir / ("coif-run-" + tag + ".out"), err = dir / ("coif-run-" + tag + ".err");
    const std::string cmd = prefix + (prefix.empty() ? "" : " ") + "'" + COIF_EXE + "' " + args + " >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_text(out);
    r.err = read_text(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

}  // namespace coif::test
