#pragma once
// coif::Error — the one error type of the project. It carries the file concerned, the place in it
// ("byte 128", "strand 17, point 3", "JSON /clusters/2/radius", "option --lights") and what is wrong.
// Libraries throw it; tools/ turns it into `coif: error: <file>: <place>: <what>` and exit code 1.
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

namespace coif {

class Error : public std::runtime_error {
public:
    Error(std::filesystem::path file, std::string place, std::string what)
        : std::runtime_error(format(file, place, what)),
          file_(std::move(file)), place_(std::move(place)), what_(std::move(what)) {}

    // An error with no file (e.g. a parameter value): "place: what".
    static Error parameter(std::string place, std::string what) { return Error({}, std::move(place), std::move(what)); }

    const std::filesystem::path& file() const noexcept { return file_; }
    const std::string& place() const noexcept { return place_; }
    const std::string& problem() const noexcept { return what_; }

private:
    static std::string format(const std::filesystem::path& file, const std::string& place, const std::string& what) {
        std::string s;
        if (!file.empty()) s += file.string() + ": ";
        if (!place.empty()) s += place + ": ";
        return s + what;
    }
    std::filesystem::path file_;
    std::string place_;
    std::string what_;
};

// A number as an error message shows it ("1e+30", "2.5", "inf"). Messages print what was read
// through this rather than through an integer cast, which is undefined for values out of range.
inline std::string number_text(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace coif
