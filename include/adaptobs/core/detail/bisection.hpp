#pragma once
/// \file
/// The boundary of a monotone predicate, by bracketing and bisection: slower
/// than Newton's method, but it cannot fail, and it runs at design time.

namespace adaptobs::detail {

/// The x ≥ 0 at which `below(x)` turns from true to false, for a predicate true
/// on [0, x*) and false beyond. The bracket starts at `start` and doubles, or
/// halves while the predicate is false (so an x* far below `start` keeps its
/// relative accuracy); 0 when it is false down to the smallest double. Stops
/// when the bracket is narrower than `relative_tolerance` of its upper end, or
/// after `max_halvings` halvings.
template <class Below>
[[nodiscard]] double boundary_by_bisection(Below below, double start = 1.0, double relative_tolerance = 1e-13,
                                           int max_halvings = 200) {
  double low = start, high = start;
  if (below(start)) {
    do {
      low = high;
      high *= 2;
    } while (below(high));
  } else {
    do {
      high = low;
      low *= 0.5;
    } while (low > 0 && !below(low));
    if (low == 0) return 0;
  }
  for (int i = 0; i < max_halvings && high - low > relative_tolerance * high; ++i) {
    const double mid = 0.5 * (low + high);
    (below(mid) ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace adaptobs::detail
