list(APPEND SSRT_SOURCES renderer/renderer.cpp)
