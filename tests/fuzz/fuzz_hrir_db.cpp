// The HRIR database reader (db/hrir_db.h HrirDatabase::open): header, JSON header, features and records.
// The file ends in an XXH3-64 of everything before it, which a mutation would almost always break; the
// target writes the right checksum over the mutated bytes so that the fuzzer reaches the header's checks.
#include <cstring>
#include <vector>

#include "db/hrir_db.h"
#include "models/core/checksum.h"
#include "tests/fuzz/fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::uint8_t> bytes(data, data + size);
    if (bytes.size() >= 8 && (bytes[0] & 1) == 0) {  // half the inputs keep their own (usually wrong) checksum
        const std::uint64_t sum = coif::checksum(std::span(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size() - 8));
        std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    }
    const auto path = coif::fuzz::input_file(bytes.data(), bytes.size(), ".db");
    coif::fuzz::refused_or_parsed([&] {
        const coif::HrirDatabase db = coif::HrirDatabase::open(path);
        if (db.size() > 0) {
            (void)db.record(0);
            (void)db.record(db.size() - 1);
        }
    });
    return 0;
}
