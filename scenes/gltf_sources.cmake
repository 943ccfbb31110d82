# The glTF 2.0 loader: beside the scene model, but in its own library so that the core
# library `ssrt` does not depend on tinygltf (see DESIGN.md).
# Debian ships tinygltf as a shared library with a CMake config (README.Debian); it carries
# its own JSON parser and image decoders, so no stb headers are needed here. It is built
# without Draco: compressed geometry (scenes/gltf_compression.h) is decoded here with Debian's
# libdraco (KHR_draco_mesh_compression) and libmeshoptimizer (EXT_meshopt_compression), and
# nlohmann-json adjusts those files' JSON before tinygltf parses it.
find_package(TinyGLTF REQUIRED)
find_package(draco REQUIRED)
find_package(meshoptimizer REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
add_library(ssrt_gltf STATIC scenes/gltf_loader.cpp scenes/gltf_textures.cpp
                             scenes/gltf_compression.cpp scenes/gltf_draco.cpp
                             scenes/gltf_meshopt.cpp scenes/gltf_camera.cpp)
target_link_libraries(ssrt_gltf PUBLIC ssrt PRIVATE ssrt_io TinyGLTF::TinyGLTF draco::draco
                                                    meshoptimizer::meshoptimizer
                                                    nlohmann_json::nlohmann_json)
