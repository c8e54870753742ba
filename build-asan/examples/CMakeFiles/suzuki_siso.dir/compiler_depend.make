# Empty compiler generated dependencies file for suzuki_siso.
# This may be replaced when dependencies are built.
