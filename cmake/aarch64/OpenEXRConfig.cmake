# OpenEXR 3.1 for the aarch64 cross build (cmake/aarch64-linux-gnu.cmake says why): the arm64
# run-time libraries of libopenexr-3-1-30:arm64 and libimath-3-1-29:arm64, the headers of the
# amd64 libopenexr-dev (byte-identical to the arm64 package's), and the imported target
# OpenEXR::OpenEXR that io/ links, as the package's own config names it. (Imath's arm64 CMake
# package is not used: it names a Python module that is not installed and warns.)
include_guard(GLOBAL)
set(OpenEXR_VERSION 3.1.5)
set(_ssrt_exr_libdir /usr/lib/aarch64-linux-gnu)
foreach(header /usr/include/OpenEXR/ImfOutputFile.h /usr/include/Imath/ImathVec.h)
    if(NOT EXISTS ${header})
        message(FATAL_ERROR "${header} is missing: install libopenexr-dev and libimath-dev")
    endif()
endforeach()
# Each library as NAME/SOVERSION/LINKS, in dependency order.
foreach(entry "Imath/29/" "Iex/30/" "IlmThread/30/OpenEXR::Iex"
              "OpenEXRCore/30/OpenEXR::Imath"
              "OpenEXR/30/OpenEXR::Iex,OpenEXR::IlmThread,OpenEXR::OpenEXRCore,OpenEXR::Imath")
    string(REPLACE "/" ";" parts "${entry}")
    list(GET parts 0 name)
    list(GET parts 1 soversion)
    list(GET parts 2 links)
    string(REPLACE "," ";" links "${links}")
    set(file ${_ssrt_exr_libdir}/lib${name}-3_1.so.${soversion})
    if(NOT EXISTS ${file})
        message(FATAL_ERROR "${file} is missing: install scripts/install-deps.sh arm's packages")
    endif()
    add_library(OpenEXR::${name} SHARED IMPORTED)
    set_target_properties(OpenEXR::${name} PROPERTIES
        IMPORTED_LOCATION ${file}
        INTERFACE_INCLUDE_DIRECTORIES "/usr/include/OpenEXR;/usr/include/Imath"
        INTERFACE_LINK_LIBRARIES "${links}")
endforeach()
set(OpenEXR_FOUND TRUE)
