#pragma once
// Little helpers for binary file layouts (coif's formats are little-endian, as the machines we run on):
// append a value's bytes to a buffer, read a value from unaligned bytes.
#include <cstddef>
#include <cstring>
#include <vector>

namespace coif::bytes {

template <class T>
void put(std::vector<std::byte>& buffer, T value) {
    const auto* p = reinterpret_cast<const std::byte*>(&value);
    buffer.insert(buffer.end(), p, p + sizeof(T));
}

template <class T>
T get(const std::byte* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    return value;
}

}  // namespace coif::bytes
