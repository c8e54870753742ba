# Empty compiler generated dependencies file for satellite.
# This may be replaced when dependencies are built.
