list(APPEND SSRT_SOURCES core/color.cpp core/image.cpp core/plane_view.cpp core/gbuffer_view.cpp core/plane_memory.cpp core/plane_pool.cpp core/fields.cpp core/isa.cpp core/tiles.cpp core/pixel_formats.cpp core/float_planes.cpp core/suggest.cpp core/profile.cpp core/ray_triangle.cpp)
list(APPEND SSRT_KERNEL_SOURCES core/lane_math_kernel.cpp core/pixel_formats_kernel.cpp)

# Valgrind's callgrind.h, where installed: core/profile.cpp's scopes then mark callgrind's counts
# (perf/callgrind_passes.py). The answer is passed on the compile line, not found by
# __has_include, so that a compiler cache's direct mode (which does not see a header appear)
# cannot hand back an object built without it.
include(CheckIncludeFileCXX)
check_include_file_cxx(valgrind/callgrind.h SSRT_HAVE_CALLGRIND_H)
if(SSRT_HAVE_CALLGRIND_H)
    set_source_files_properties(core/profile.cpp PROPERTIES COMPILE_DEFINITIONS SSRT_CALLGRIND=1)
else()
    set_source_files_properties(core/profile.cpp PROPERTIES COMPILE_DEFINITIONS SSRT_CALLGRIND=0)
endif()
