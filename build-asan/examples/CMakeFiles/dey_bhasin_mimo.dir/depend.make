# Empty dependencies file for dey_bhasin_mimo.
# This may be replaced when dependencies are built.
