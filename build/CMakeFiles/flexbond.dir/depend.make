# Empty dependencies file for flexbond.
# This may be replaced when dependencies are built.
