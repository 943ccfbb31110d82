list(APPEND SSRT_SOURCES scenes/scene.cpp scenes/mesh_builders.cpp scenes/builtin_scenes.cpp
     scenes/failure_scenes.cpp scenes/camera_path.cpp)
