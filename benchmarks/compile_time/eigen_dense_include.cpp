// Compile-time benchmark, hand-written side: the cost of <Eigen/Dense> alone.
// Paired with umbrella_include.cpp.

#include <Eigen/Dense>

int main() {}
