# Empty compiler generated dependencies file for test_augmented_kalman.
# This may be replaced when dependencies are built.
