list(APPEND SSRT_SOURCES raster/geometry.cpp raster/alpha_test.cpp raster/binning.cpp
     raster/raster.cpp raster/shadow_map.cpp raster/hiz.cpp raster/back_depth.cpp)
list(APPEND SSRT_KERNEL_SOURCES raster/tile_raster_kernel.cpp raster/resolve_kernel.cpp)
