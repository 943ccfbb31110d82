# world/: Embree's scene, world-space rays and the light of a world hit. A library of its own
# so that the core library never links Embree (DESIGN.md); the truth builds on it.
find_package(embree 3 REQUIRED)
add_library(ssrt_world STATIC
    ${CMAKE_CURRENT_LIST_DIR}/embree_scene.cpp
    ${CMAKE_CURRENT_LIST_DIR}/embree_world_rays.cpp
    ${CMAKE_CURRENT_LIST_DIR}/hit_light.cpp)
target_link_libraries(ssrt_world PUBLIC ssrt PRIVATE embree)
