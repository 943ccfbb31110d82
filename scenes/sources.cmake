list(APPEND SSRT_SOURCES scenes/scene.cpp)
