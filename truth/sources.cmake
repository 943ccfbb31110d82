# truth/: the Embree truth (BVH, ray checks, reference image, image error). A
# library of its own so that the core library never links Embree (DESIGN.md).
find_package(embree 3 REQUIRED)
add_library(ssrt_truth STATIC
    ${CMAKE_CURRENT_LIST_DIR}/embree_scene.cpp
    ${CMAKE_CURRENT_LIST_DIR}/evaluation.cpp
    ${CMAKE_CURRENT_LIST_DIR}/image_error.cpp
    ${CMAKE_CURRENT_LIST_DIR}/parts.cpp
    ${CMAKE_CURRENT_LIST_DIR}/ray_check.cpp
    ${CMAKE_CURRENT_LIST_DIR}/reference_image.cpp
    ${CMAKE_CURRENT_LIST_DIR}/reference_key.cpp
    ${CMAKE_CURRENT_LIST_DIR}/reference_shading.cpp)
target_link_libraries(ssrt_truth PUBLIC ssrt PRIVATE embree)
