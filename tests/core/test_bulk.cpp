// Bulk<T> (models/core/bulk.h): an owned array behaves as the vector it replaces; a viewed one reads the memory
// it views, keeps it alive, and becomes owned before it is changed.
#include <gtest/gtest.h>

#include <memory>
#include <numeric>
#include <vector>

#include "models/core/bulk.h"

namespace coif {
namespace {

TEST(Bulk, OwnedBehavesAsItsVector) {
    Bulk<int> a = std::vector<int>{1, 2, 3};
    EXPECT_FALSE(a.viewed());
    EXPECT_EQ(a.size(), 3u);
    EXPECT_EQ(std::accumulate(a.begin(), a.end(), 0), 6);
    Bulk<int> b = a;  // a copy owns its own elements
    b.vector().push_back(4);
    EXPECT_EQ(a.size(), 3u);
    EXPECT_EQ(b.size(), 4u);
    EXPECT_EQ(b[3], 4);
    Bulk<int> c = std::move(b);
    EXPECT_EQ(c.size(), 4u);
    EXPECT_TRUE(b.empty());  // NOLINT(bugprone-use-after-move): moved-from is empty
    EXPECT_THROW((void)c.at(4), std::out_of_range);
}

TEST(Bulk, ViewedKeepsItsMemoryAliveAndCopiesBeforeAChange) {
    auto memory = std::make_shared<std::vector<int>>(std::vector<int>{5, 6, 7});
    std::weak_ptr<std::vector<int>> alive = memory;
    Bulk<int> a(std::span<const int>(*memory), memory);
    memory.reset();
    ASSERT_FALSE(alive.expired()) << "the view keeps its memory";
    EXPECT_TRUE(a.viewed());
    EXPECT_EQ(a.data(), alive.lock()->data()) << "viewed, not copied";
    Bulk<int> b = a;  // copies share the view
    EXPECT_EQ(b.data(), a.data());
    a.vector()[0] = 50;  // a change: a copies first, b and the memory are untouched
    EXPECT_FALSE(a.viewed());
    EXPECT_EQ(a[0], 50);
    EXPECT_EQ(b[0], 5);
    EXPECT_EQ((*alive.lock())[0], 5);
    b = Bulk<int>();
    EXPECT_TRUE(alive.expired()) << "the last view gone, the memory is released";
}

}  // namespace
}  // namespace coif
