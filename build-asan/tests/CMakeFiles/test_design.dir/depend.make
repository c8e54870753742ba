# Empty dependencies file for test_design.
# This may be replaced when dependencies are built.
