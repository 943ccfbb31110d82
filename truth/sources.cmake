# truth/: the Embree truth (ray checks, reference image, image error), on world/'s scene.
add_library(ssrt_truth STATIC
    ${CMAKE_CURRENT_LIST_DIR}/evaluation.cpp
    ${CMAKE_CURRENT_LIST_DIR}/image_error.cpp
    ${CMAKE_CURRENT_LIST_DIR}/parts.cpp
    ${CMAKE_CURRENT_LIST_DIR}/ray_check.cpp
    ${CMAKE_CURRENT_LIST_DIR}/reference_image.cpp
    ${CMAKE_CURRENT_LIST_DIR}/reference_key.cpp)
target_link_libraries(ssrt_truth PUBLIC ssrt ssrt_world)
