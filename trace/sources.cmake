list(APPEND SSRT_SOURCES trace/trace_types.cpp)
list(APPEND SSRT_SOURCES trace/color_pyramid.cpp trace/ssr_resolve.cpp trace/ssgi.cpp)
list(APPEND SSRT_KERNEL_SOURCES trace/ssr_resolve_kernel.cpp trace/ssgi_kernel.cpp)
