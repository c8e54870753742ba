// Compile-time benchmark, library side: the cost of the umbrella header alone.
// Paired with eigen_dense_include.cpp.

#include <adaptobs/adaptobs.hpp>

int main() {}
