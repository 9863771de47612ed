#include "core/result.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace dpscope {
namespace {

struct Base {
    virtual ~Base() = default;
    virtual int id() const { return 1; }
};
struct Derived : Base {
    int id() const override { return 2; }
};

Result<int> half(int n) {
    if (n % 2 != 0) return Error{"odd: " + std::to_string(n)};
    return n / 2;
}

TEST(ResultTest, HoldsAValue) {
    Result<int> result = half(8);
    ASSERT_TRUE(result.has_value());
    EXPECT_TRUE(static_cast<bool>(result));
    EXPECT_EQ(result.value(), 4);
    EXPECT_EQ(*result, 4);
    EXPECT_EQ(result.error(), "");
}

TEST(ResultTest, HoldsAnErrorMessage) {
    Result<int> result = half(7);
    EXPECT_FALSE(result.has_value());
    EXPECT_FALSE(static_cast<bool>(result));
    EXPECT_EQ(result.error(), "odd: 7");
}

TEST(ResultTest, AStringValueIsNoError) {
    Result<std::string> value = std::string("text");
    Result<std::string> error = Error{"text"};
    ASSERT_TRUE(value);
    EXPECT_EQ(*value, "text");
    EXPECT_EQ(value->size(), 4u);
    EXPECT_FALSE(error);
    EXPECT_EQ(error.error(), "text");
}

TEST(ResultTest, MovesAMoveOnlyValueOut) {
    Result<std::unique_ptr<Base>> result = std::make_unique<Derived>();
    ASSERT_TRUE(result);
    EXPECT_EQ((*result)->id(), 2);
    std::unique_ptr<Base> taken = std::move(result).value();
    ASSERT_NE(taken, nullptr);
    EXPECT_EQ(taken->id(), 2);
}

TEST(ResultTest, ValueIsModifiable) {
    Result<std::vector<int>> result = std::vector<int>{1, 2};
    result->push_back(3);
    result.value().push_back(4);
    EXPECT_EQ(*result, (std::vector<int>{1, 2, 3, 4}));
}

Result<void> require_even(int n) {
    if (n % 2 != 0) return Error{"odd: " + std::to_string(n)};
    return {};
}

TEST(ResultTest, VoidResultSucceedsWithoutAValue) {
    Result<void> result = require_even(4);
    EXPECT_TRUE(result.has_value());
    EXPECT_TRUE(static_cast<bool>(result));
    EXPECT_EQ(result.error(), "");
}

TEST(ResultTest, VoidResultHoldsAnErrorMessage) {
    Result<void> result = require_even(3);
    EXPECT_FALSE(result.has_value());
    EXPECT_EQ(result.error(), "odd: 3");
}

TEST(ResultTest, VoidResultFailsEvenWithAnEmptyMessage) {
    Result<void> result = Error{};
    EXPECT_FALSE(result);
}

}  // namespace
}  // namespace dpscope
