list(APPEND SSRT_SOURCES denoise/denoise.cpp)
list(APPEND SSRT_KERNEL_SOURCES denoise/reblur_kernel.cpp)
