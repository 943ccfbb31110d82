list(APPEND SSRT_SOURCES denoise/denoise.cpp)
list(APPEND SSRT_KERNEL_SOURCES denoise/front_end_kernel.cpp denoise/spatial_kernel.cpp
     denoise/temporal_kernel.cpp denoise/history_fix_kernel.cpp)
