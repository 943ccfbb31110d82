list(APPEND SSRT_SOURCES trace/trace_types.cpp)
