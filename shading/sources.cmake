
list(APPEND SSRT_KERNEL_SOURCES shading/sampling_kernel.cpp)
list(APPEND SSRT_KERNEL_SOURCES shading/direct_kernel.cpp)
list(APPEND SSRT_SOURCES shading/energy_tables.cpp)
list(APPEND SSRT_SOURCES shading/environment.cpp)
list(APPEND SSRT_SOURCES shading/prefiltered_env.cpp)
list(APPEND SSRT_SOURCES shading/irradiance_sh.cpp)
list(APPEND SSRT_KERNEL_SOURCES shading/composite_kernel.cpp)
list(APPEND SSRT_SOURCES shading/composite.cpp)
