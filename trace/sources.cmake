list(APPEND SSRT_SOURCES trace/trace_types.cpp trace/march.cpp)
list(APPEND SSRT_KERNEL_SOURCES trace/march_linear.cpp trace/march_dda.cpp trace/march_hiz.cpp)
