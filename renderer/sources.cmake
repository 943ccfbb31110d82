list(APPEND SSRT_SOURCES renderer/direct_lighting.cpp renderer/frame_graph.cpp renderer/resources.cpp renderer/frame_graph_decl.cpp renderer/frame_scheduler.cpp renderer/layer_groups.cpp renderer/memory_use.cpp renderer/renderer.cpp renderer/resolve_tables.cpp renderer/settings.cpp renderer/sky_lighting.cpp renderer/texture_pass.cpp
     renderer/trace_pass.cpp renderer/quality.cpp)
