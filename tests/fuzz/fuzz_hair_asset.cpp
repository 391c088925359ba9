// The `.coif` hair asset reader (online/shells/hair_asset.h parse_hair_asset): header, metadata JSON, sections and
// every count and index they must agree on. Bytes 24..31 hold an XXH3-64 of everything after the header, which a
// mutation would almost always break; for half the inputs the target writes the right checksum over the mutated
// bytes so that the fuzzer reaches the checks behind it.
#include <cstring>
#include <vector>

#include "models/core/checksum.h"
#include "online/shells/hair_asset.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::byte> bytes(size);
    if (size) std::memcpy(bytes.data(), data, size);
    if (bytes.size() >= 32 && (std::to_integer<int>(bytes[0]) & 1) == 0) {
        const std::uint64_t sum = coif::checksum(std::span<const std::byte>(bytes).subspan(32));
        std::memcpy(bytes.data() + 24, &sum, 8);
    }
    // Byte 0 chose the checksum; the magic's first letter is restored so that the rest is reached.
    if (!bytes.empty()) bytes[0] = std::byte{'C'};
    coif::fuzz::refused_or_parsed([&] { (void)coif::parse_hair_asset(bytes, "input.coif"); });
    return 0;
}
