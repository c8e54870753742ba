#pragma once
/// \file
/// Design routines compiled once, for programs that link `adaptobs::precompiled`.
///
/// The dense decompositions behind design routines (eigenvalues, Schur forms,
/// LU and Cholesky factorizations on dynamic sizes)
/// are costly to compile in every translation unit that calls them. Each such
/// routine therefore runs on dynamic-size matrices through one public function
/// template per scalar type, named `<routine>_dynamic` and taking
/// `Eigen::MatrixX<Scalar>` (`place_output_injection_dynamic`,
/// `design_guiro_gains_dynamic`, `observability_staircase`, ...); the routine
/// itself, for fixed-size or expression arguments, copies them and sizes the
/// result. A `_dynamic` routine's refusals name the routine without the suffix.
/// The optional library `adaptobs::precompiled`
/// (src/precompiled/, several translation units, each the definitions of some
/// headers' lines) instantiates those templates for `double` (the matrix
/// exponential, which sampled float models also call, for `float` too), and whatever
/// links it is compiled with `ADAPTOBS_PRECOMPILED` defined. That turns the
/// `ADAPTOBS_INSTANTIATE` lines after each routine into explicit instantiation
/// declarations (`extern template`): the translation unit calls the compiled
/// code instead of instantiating its own. Without the library nothing changes:
/// the headers stay header-only and instantiate what they use.
///
/// Build the library with the same architecture flags (`-march`, `-mavx`, ...)
/// as the program: Eigen objects compiled for different vector instructions
/// have different alignment and must not be passed between the two.

#if defined(ADAPTOBS_PRECOMPILED) && !defined(ADAPTOBS_INSTANTIATE)
#define ADAPTOBS_INSTANTIATE extern template
#endif
