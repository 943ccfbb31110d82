list(APPEND SSRT_SOURCES trace/ray_gen.cpp trace/march.cpp trace/hit_proof.cpp
     trace/color_pyramid.cpp trace/ssr_resolve.cpp trace/ssgi.cpp trace/hit_stats.cpp
     trace/trace_layout.cpp trace/reconstruct.cpp trace/tile_chain.cpp)
list(APPEND SSRT_KERNEL_SOURCES trace/ray_gen_kernel.cpp trace/march_linear_kernel.cpp
     trace/march_dda_kernel.cpp trace/march_hiz_kernel.cpp trace/march_keys_kernel.cpp
     trace/ssr_resolve_kernel.cpp trace/ssgi_kernel.cpp trace/hit_stats_kernel.cpp
     trace/reconstruct_kernel.cpp)
