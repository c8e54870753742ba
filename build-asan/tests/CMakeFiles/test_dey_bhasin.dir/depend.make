# Empty dependencies file for test_dey_bhasin.
# This may be replaced when dependencies are built.
