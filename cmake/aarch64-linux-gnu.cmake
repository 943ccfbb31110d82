# Cross build for aarch64 on an x86-64 Debian 12 host (scripts/test-arm.sh):
#   cmake -S . -B build-arm -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake
# Debian's cross compiler (g++-aarch64-linux-gnu) and Debian's arm64 libraries, installed
# beside the amd64 ones through multiarch (dpkg --add-architecture arm64): headers in
# /usr/include, libraries and CMake packages in /usr/lib/aarch64-linux-gnu, which the cross
# compiler and linker search by themselves. The binaries run under qemu-aarch64.
#
# Two of the renderer's libraries cannot be installed for arm64 beside the amd64 host build:
# libopenexr-dev is not Multi-Arch: same, so its arm64 copy replaces the amd64 one (and apt
# then removes libopenimageio-dev, which depends on it). The cross build therefore
#  - links OpenEXR's arm64 run-time library (libopenexr-3-1-30:arm64) through the package in
#    cmake/aarch64/, with the amd64 package's headers (byte-identical to the arm64 ones);
#  - leaves OpenImageIO out (SSRT_WITH_OIIO=OFF): ssrt's module for formats other than PNG,
#    JPEG, HDR and EXR, and the tests that compare with OpenImageIO.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# The loader and libraries of the arm64 packages are where qemu looks by default (/lib,
# /usr/lib/aarch64-linux-gnu), so no -L prefix is needed.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64)

set(OpenEXR_DIR ${CMAKE_CURRENT_LIST_DIR}/aarch64 CACHE PATH "OpenEXR for the aarch64 build")
set(SSRT_WITH_OIIO OFF CACHE BOOL "No arm64 OpenImageIO beside the amd64 one (see above)")
