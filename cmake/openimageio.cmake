# OpenImageIO, found once for every project that reads or writes images (the main build and
# tests/fuzz). Debian 12's OpenImageIO config names /usr/include/opencv4 even when OpenCV is
# not installed; include paths that do not exist are dropped instead of pulling in OpenCV.
find_package(OpenImageIO REQUIRED)
get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
set(_oiio_kept)
foreach(_dir ${_oiio_inc})
    if(EXISTS "${_dir}")
        list(APPEND _oiio_kept "${_dir}")
    endif()
endforeach()
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES
                      INTERFACE_INCLUDE_DIRECTORIES "${_oiio_kept}")
