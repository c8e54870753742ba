// The allocation counter itself (support/allocation_counter.hpp), which the
// observer contract uses to check that fixed-size updates do not allocate: it
// sees operator new and Eigen's malloc.

#include "support/allocation_counter.hpp"

#include <Eigen/Core>

#include <gtest/gtest.h>

#include <vector>

namespace {

using adaptobs::testing::allocations_during;

// Stores through a volatile pointer, so the compiler cannot elide the allocations.
std::vector<double>* volatile sink = nullptr;

TEST(NoAllocation, CounterSeesAllocations) {
  EXPECT_EQ(allocations_during([] {
              sink = new std::vector<double>(10);  // the vector object and its buffer
              delete sink;
            }),
            2);
}

// Eigen allocates with std::malloc, which a replaced operator new never sees.
volatile double eigen_sink = 0;

TEST(NoAllocation, CounterSeesEigensMalloc) {
  EXPECT_EQ(allocations_during([] {
              const Eigen::MatrixXd m = Eigen::MatrixXd::Constant(7, 9, 0.5);
              eigen_sink = m.sum();
            }),
            1);
}

}  // namespace
