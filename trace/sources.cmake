list(APPEND SSRT_SOURCES trace/trace_types.cpp)
list(APPEND SSRT_SOURCES trace/ray_gen.cpp)
list(APPEND SSRT_KERNEL_SOURCES trace/ray_gen_kernel.cpp)
