#pragma once
// Checksums of file contents (databases, source maps of fitted lights): XXH3-64 from Debian's
// libxxhash, printed as 16 lower-case hex digits.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace coif {

std::uint64_t checksum(std::span<const std::byte> bytes);

// Incremental form, for data written in pieces.
class Checksum {
public:
    Checksum();
    ~Checksum();
    Checksum(const Checksum&) = delete;
    Checksum& operator=(const Checksum&) = delete;
    void update(std::span<const std::byte> bytes);
    std::uint64_t digest() const;

private:
    void* state_;
};

std::string checksum_hex(std::uint64_t value);

}  // namespace coif
