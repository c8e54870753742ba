# Empty dependencies file for test_discretization.
# This may be replaced when dependencies are built.
