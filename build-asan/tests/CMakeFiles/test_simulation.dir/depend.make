# Empty dependencies file for test_simulation.
# This may be replaced when dependencies are built.
