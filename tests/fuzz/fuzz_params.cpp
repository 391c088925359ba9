// The hair and renderer parameters file (online/shells/shell_settings.h read_shell_settings).
#include "online/shells/shell_settings.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = coif::fuzz::input_file(data, size, ".json");
    coif::fuzz::refused_or_parsed([&] { coif::gl::read_shell_settings(path.string()); });
    return 0;
}
