# Empty dependencies file for test_guyader_zhang.
# This may be replaced when dependencies are built.
