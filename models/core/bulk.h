#pragma once
// Bulk<T>: a read-only array that either owns its elements (a std::vector) or views them in memory that someone
// else keeps alive, such as a mapped file. It is how a cooked asset (online/shells/hair_asset.h) hands its large
// arrays to the GPU straight from the mapping: on a machine where each first write to a fresh page is expensive,
// copying 25 MB into vectors before uploading it doubled the load time (docs/renderer.md has the figures).
//
// Reading is through data(), size(), operator[] and iteration, as for a const vector. A writer builds a vector
// and assigns it; vector() gives mutable access and first copies a viewed array into owned storage.
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace coif {

template <class T>
class Bulk {
public:
    Bulk() = default;
    Bulk(std::vector<T> owned) : owned_(std::move(owned)) {}  // NOLINT: converts as the vector it replaces
    // Views `items`, which stay valid as long as `keeper` lives.
    Bulk(std::span<const T> items, std::shared_ptr<const void> keeper) : view_(items), keeper_(std::move(keeper)) {}

    std::span<const T> span() const { return keeper_ ? view_ : std::span<const T>(owned_); }
    operator std::span<const T>() const { return span(); }  // NOLINT: converts as the vector it replaces
    const T* data() const { return span().data(); }
    std::size_t size() const { return span().size(); }
    bool empty() const { return size() == 0; }
    const T& operator[](std::size_t i) const { return span()[i]; }
    const T& at(std::size_t i) const {
        if (i >= size()) throw std::out_of_range("Bulk::at");
        return span()[i];
    }
    auto begin() const { return span().begin(); }
    auto end() const { return span().end(); }
    bool viewed() const { return static_cast<bool>(keeper_); }  // whether it views memory it does not own

    // Mutable access; a viewed array is first copied into owned storage.
    std::vector<T>& vector() {
        if (keeper_) {
            owned_.assign(view_.begin(), view_.end());
            view_ = {};
            keeper_.reset();
        }
        return owned_;
    }

private:
    std::vector<T> owned_;
    std::span<const T> view_;             // when viewed
    std::shared_ptr<const void> keeper_;  // keeps the viewed memory alive
};

}  // namespace coif
