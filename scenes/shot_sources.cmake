# Shot files (JSON): beside the scene model, in their own library so that the core library
# `ssrt` does not depend on a JSON parser (see DESIGN.md). Debian: nlohmann-json3-dev.
find_package(nlohmann_json 3.10 REQUIRED)
add_library(ssrt_shot STATIC scenes/shot.cpp)
target_link_libraries(ssrt_shot PUBLIC ssrt PRIVATE nlohmann_json::nlohmann_json)
