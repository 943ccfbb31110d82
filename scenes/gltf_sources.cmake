# The glTF 2.0 loader: beside the scene model, but in its own library so that the core
# library `ssrt` does not depend on tinygltf (see DESIGN.md).
# Debian ships tinygltf as a shared library with a CMake config (README.Debian); it carries
# its own JSON parser and image decoders, so no nlohmann-json or stb headers are needed here.
find_package(TinyGLTF REQUIRED)
add_library(ssrt_gltf STATIC scenes/gltf_loader.cpp scenes/gltf_textures.cpp)
target_link_libraries(ssrt_gltf PUBLIC ssrt PRIVATE ssrt_io TinyGLTF::TinyGLTF)
