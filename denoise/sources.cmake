list(APPEND SSRT_SOURCES denoise/denoise.cpp)
list(APPEND SSRT_SOURCES
     denoise/reconstruct.cpp
)
list(APPEND SSRT_KERNEL_SOURCES denoise/reblur_kernel.cpp)
list(APPEND SSRT_KERNEL_SOURCES
     denoise/reconstruct_kernel.cpp
)
