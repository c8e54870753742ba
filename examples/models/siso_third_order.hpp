#pragma once
/// \file
/// A third-order SISO plant that is *not* in any canonical form, used by the
/// `bastin_gevers`, `marino_tomei` and `unified_comparison` examples, the tests
/// and the benchmarks (Zhang 2005 prints no example; this is the plant of the
/// library's verification of §III-A/B):
/// \f[ \dot\eta = \begin{bmatrix} -1 & 2 & 0\\ -1 & -1 & 1\\ 0.5 & 0 & -2\end{bmatrix}\eta
///     + \begin{bmatrix} 0\\ 1\\ 0.5\end{bmatrix}u + \Phi(t)\theta,\qquad y = [1\ 0\ 1]\,\eta, \f]
/// \f$\Phi(t) = \begin{bmatrix} \sin t & 0\\ \cos 1.7t & 1\\ 0 & \sin 0.6t\end{bmatrix}\f$,
/// θ = (2, −1), u = 1 + sin 0.3t, η(0) = (1, −1, 0.5).
/// \f$\det(sI - A) = s^3 + 4s^2 + 7s + 5\f$ (poles −1.215 ± 1.307i, −1.570); (A, C) observable.

#include <adaptobs/core/continuous_model.hpp>
#include <adaptobs/core/dimensions.hpp>
#include <adaptobs/simulation/continuous_plant.hpp>

#include <cmath>

namespace adaptobs::examples::siso {

template <typename S>
using Dims = Dimensions<S, 3, 1, 1, 2>;

template <typename S>
Eigen::Matrix<S, 3, 3> dynamics() {
  Eigen::Matrix<S, 3, 3> a;
  a << -1, 2, 0,  //
      -1, -1, 1,  //
      S(0.5), 0, -2;
  return a;
}
template <typename S>
Eigen::Matrix<S, 3, 1> input_matrix() {
  return {S(0), S(1), S(0.5)};
}
template <typename S>
Eigen::Matrix<S, 1, 3> output_matrix() {
  return {S(1), S(0), S(1)};
}
template <typename S>
Eigen::Matrix<S, 2, 1> true_parameters() {
  return {S(2), S(-1)};
}
template <typename S>
Eigen::Matrix<S, 3, 1> initial_state() {
  return {S(1), S(-1), S(0.5)};
}

/// \f$\Phi(t)\f$.
struct Regressor {
  template <typename S>
  Eigen::Matrix<S, 3, 2> operator()(S t) const {
    Eigen::Matrix<S, 3, 2> phi;
    phi << std::sin(t), S(0),        //
        std::cos(S(1.7) * t), S(1),  //
        S(0), std::sin(S(0.6) * t);
    return phi;
  }
};

/// u(t) = 1 + sin 0.3t.
struct Input {
  template <typename S>
  Eigen::Matrix<S, 1, 1> operator()(S t) const {
    return Eigen::Matrix<S, 1, 1>(S(1) + std::sin(S(0.3) * t));
  }
};

template <typename S>
auto model() {
  return make_continuous_lti_model<Dims<S>>(dynamics<S>(), input_matrix<S>(), output_matrix<S>(),
                                            [](S t) { return Regressor{}.operator()<S>(t); });
}

template <typename S>
using Model = decltype(model<S>());

template <typename S>
auto make_plant(ContinuousPlantOptions<S> options = {}) {
  return ContinuousLinearPlant(
      model<S>(), initial_state<S>(), true_parameters<S>(), [](S t) { return Input{}.operator()<S>(t); }, options);
}

}  // namespace adaptobs::examples::siso
