#pragma once
/// \file
/// Segments of a vector whose length may or may not be known at compile time:
/// `segment<Size>(v, start, size)` is a fixed-size block when `Size` is fixed
/// (so that the products it enters are unrolled) and a dynamic one otherwise.
/// (Eigen 3.4.0's `tail<Dynamic>(n)` does not compile, hence this helper.)

#include <Eigen/Core>

namespace adaptobs::detail {

template <int Size, class Vector>
[[nodiscard]] auto segment(Vector&& v, Eigen::Index start, Eigen::Index size) {
  if constexpr (Size == Eigen::Dynamic) {
    return v.segment(start, size);
  } else {
    return v.template segment<Size>(start);
  }
}

}  // namespace adaptobs::detail
