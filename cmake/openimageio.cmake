# OpenImageIO, found once for every project that reads or writes images (the main build and
# tests/fuzz), through its pkg-config file rather than its CMake package. Debian 12's CMake
# package (OpenImageIOTargets.cmake) fails the configure step unless the command-line tools of
# openimageio-tools exist (iconvert, idiff, ...), a package the renderer never runs and that
# pulls in Qt 5; it also names /usr/include/opencv4 whether or not OpenCV is installed.
# libopenimageio-dev ships OpenImageIO.pc, which names the library and its headers only.
include_guard(GLOBAL)
find_package(PkgConfig REQUIRED)
pkg_check_modules(OpenImageIO REQUIRED IMPORTED_TARGET GLOBAL OpenImageIO)
add_library(OpenImageIO::OpenImageIO ALIAS PkgConfig::OpenImageIO)
