list(APPEND SSRT_SOURCES core/color.cpp core/image.cpp core/plane_view.cpp core/gbuffer_view.cpp core/plane_memory.cpp core/plane_pool.cpp core/fields.cpp core/isa.cpp core/tiles.cpp core/pixel_formats.cpp core/float_planes.cpp core/suggest.cpp core/profile.cpp)
list(APPEND SSRT_KERNEL_SOURCES core/lane_math_kernel.cpp core/pixel_formats_kernel.cpp)
