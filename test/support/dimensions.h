// Typed tests over the dimension, for the code that is a template over D (Body<D>, the stages,
// LeakyDielectricSolver<D>, ImmersedBoundaryTransfer<D>, Grid<D>):
//
//   template <typename Dim> class SpreadStageTest : public ::testing::Test {};
//   TYPED_TEST_SUITE(SpreadStageTest, ehd::test::BothDimensions, ehd::test::DimensionName);
//   TYPED_TEST(SpreadStageTest, ConservesTheForce) {
//     constexpr int D = TypeParam::value;
//     ...
//   }
//
// The tests are named ".../D2" and ".../D3" (gtest_filter '*D3*' runs the 3D ones).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <type_traits>

namespace ehd::test {

template <int D>
using Dimension = std::integral_constant<int, D>;

using BothDimensions = ::testing::Types<Dimension<2>, Dimension<3>>;

struct DimensionName {
  template <typename T>
  static std::string GetName(int) {
    return "D" + std::to_string(T::value);
  }
};

}  // namespace ehd::test
