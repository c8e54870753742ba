# Empty dependencies file for test_no_allocation.
# This may be replaced when dependencies are built.
