# Debian 12's OpenImageIO CMake package cannot be used as shipped: its target
# file references /usr/bin/iconvert (only in openimageio-tools) and its
# include directories name a missing /usr/include/opencv4. Its pkg-config
# file is complete, so strata takes OpenImageIO from there.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
