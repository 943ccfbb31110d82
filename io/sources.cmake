# io/: image files at the edge, each format through its own library (see README.md, "Image
# files"). Included by the main build and by tests/fuzz; `root` is the source root.
#
# SSRT_IO_DECODE_SOURCES: decoding images (what textures need); ssrt_io adds the writers, sky
# images and comparisons. The OpenImageIO module (ssrt_oiio.so) is built by
# ssrt_add_oiio_module and dlopen()ed by io/oiio_module.cpp when a file needs it.
# SSRT_WITH_OIIO=OFF leaves the module out (the aarch64 build: Debian 12's arm64 OpenImageIO
# cannot be installed beside the amd64 one, see cmake/aarch64-linux-gnu.cmake); such a file then
# fails with the module's one-line error, as where the module is not installed.
option(SSRT_WITH_OIIO "Build the OpenImageIO module for image formats other than PNG, JPEG, HDR \
and EXR, and the tests that compare with OpenImageIO" ON)
if(SSRT_WITH_OIIO)
    include(${root}/cmake/openimageio.cmake)
endif()
find_package(PNG REQUIRED)
find_package(JPEG REQUIRED)
find_package(OpenEXR REQUIRED)
include(GNUInstallDirs)

set(SSRT_IO_DECODE_SOURCES
    ${root}/io/decoded_image.cpp ${root}/io/exr_channel_order.cpp ${root}/io/exr_imf_pixels.cpp
    ${root}/io/exr_input.cpp ${root}/io/hdr_io.cpp
    ${root}/io/image_decode.cpp ${root}/io/jpeg_io.cpp ${root}/io/oiio_module.cpp
    ${root}/io/png_io.cpp ${root}/io/texture_io.cpp)
set(SSRT_IO_DECODE_LIBRARIES PNG::PNG JPEG::JPEG OpenEXR::OpenEXR OpenEXR::OpenEXRCore
                              ${CMAKE_DL_LIBS})

# Where io/oiio_module.cpp looks for the module (besides beside the program): the build tree,
# an absolute path given to that one file only (so the others compile to the same command line
# in any checkout, for the compiler cache), and <prefix>/<libdir>/ssrt relative to the program.
set_property(SOURCE ${root}/io/oiio_module.cpp APPEND PROPERTY COMPILE_DEFINITIONS
             SSRT_OIIO_MODULE_BUILD_DIR="${CMAKE_BINARY_DIR}")
set_property(SOURCE ${root}/io/oiio_module.cpp APPEND PROPERTY COMPILE_DEFINITIONS
             SSRT_INSTALL_LIBDIR="${CMAKE_INSTALL_LIBDIR}")

# The module, in the build tree's top folder (beside build/ssrt).
function(ssrt_add_oiio_module)
    if(NOT SSRT_WITH_OIIO)
        return()
    endif()
    add_library(ssrt_oiio MODULE ${root}/io/oiio_plugin.cpp)
    set_target_properties(ssrt_oiio PROPERTIES PREFIX ""
                                               LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})
    target_include_directories(ssrt_oiio PRIVATE ${root})
    target_link_libraries(ssrt_oiio PRIVATE OpenImageIO::OpenImageIO)
endfunction()
