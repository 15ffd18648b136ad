#include "spatter/core/Result.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

using namespace spatter;

// A Result gives its value as value(), *r and r->, and moves it out of an rvalue; a failed one gives
// its error and no value.
TEST(Result, GivesItsValueByValueStarAndArrowAndMovesItOut) {
    Result<std::string> r(std::string("decal"));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(*r, "decal");
    EXPECT_EQ(r->size(), 5u);
    (*r)[0] = 'D';
    EXPECT_EQ(r.value(), "Decal");
    const Result<std::string>& constant = r;
    EXPECT_EQ(*constant, "Decal");
    EXPECT_TRUE(r.error().empty());

    Result<std::unique_ptr<int>> owner(std::make_unique<int>(7));
    const std::unique_ptr<int> taken = *std::move(owner);
    ASSERT_NE(taken, nullptr);
    EXPECT_EQ(*taken, 7);

    const Result<int> failed = fail("no proxy");
    EXPECT_FALSE(failed.ok());
    EXPECT_FALSE(bool(failed));
    EXPECT_EQ(failed.error(), "no proxy");
}
