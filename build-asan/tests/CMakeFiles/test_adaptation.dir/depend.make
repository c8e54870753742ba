# Empty dependencies file for test_adaptation.
# This may be replaced when dependencies are built.
