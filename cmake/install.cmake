# The installed package: find_package(ssrt REQUIRED COMPONENTS core io gltf shot world truth).
#
# Each component is one imported target with its own export file, so that a tool pays only
# for the libraries it asks for: core (ssrt::ssrt, also ssrt::core: GLM, xsimd, oneTBB),
# io (ssrt::io: libpng, libjpeg, OpenEXR; OpenImageIO only in the module it loads on need),
# gltf (ssrt::gltf: tinygltf, Draco, meshoptimizer; needs io for textures), shot
# (ssrt::shot: nlohmann-json), world (ssrt::world: Embree 3) and truth (ssrt::truth: needs
# world). The libraries are static, so each one's private libraries are named in its export
# file and found again by cmake/ssrtConfig.cmake.in, component by component.
include(CMakePackageConfigHelpers)
set(SSRT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ssrt)

# Headers: every module's, but those only the per-ISA kernel sources include (they need the
# ISA macros of cmake/kernels.cmake and are no API). Every installed header compiles on its
# own: tests/install checks that.
set(SSRT_KERNEL_ONLY_HEADERS core/isa_target.h denoise/reblur_lanes.h trace/march_common.h)
function(ssrt_install_headers)
    foreach(dir ${ARGN})
        file(GLOB headers RELATIVE ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/${dir}/*.h)
        list(REMOVE_ITEM headers ${SSRT_KERNEL_ONLY_HEADERS})
        install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ssrt/${dir})
    endforeach()
endfunction()

# The core library.
install(TARGETS ssrt EXPORT ssrtTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ssrt)
ssrt_install_headers(core scenes raster shading trace denoise renderer)
install(EXPORT ssrtTargets NAMESPACE ssrt:: DESTINATION ${SSRT_CMAKE_DIR})
set(SSRT_COMPONENTS core)

# The components beside it, where this build has them: target, component, header folders.
function(ssrt_install_component target component)
    if(NOT TARGET ${target})
        return()
    endif()
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${component})
    install(TARGETS ${target} EXPORT ssrt_${component}Targets
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
    ssrt_install_headers(${ARGN})
    install(EXPORT ssrt_${component}Targets NAMESPACE ssrt::
            FILE ssrt-${component}-targets.cmake DESTINATION ${SSRT_CMAKE_DIR})
    set(SSRT_COMPONENTS ${SSRT_COMPONENTS} ${component} PARENT_SCOPE)
endfunction()
ssrt_install_component(ssrt_io io io)
ssrt_install_component(ssrt_gltf gltf)  # its headers are scenes/'s, installed with the core
ssrt_install_component(ssrt_shot shot)
ssrt_install_component(ssrt_world world world)
ssrt_install_component(ssrt_truth truth truth)

configure_package_config_file(cmake/ssrtConfig.cmake.in
    ${CMAKE_CURRENT_BINARY_DIR}/ssrtConfig.cmake
    INSTALL_DESTINATION ${SSRT_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/ssrtConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ssrtConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/ssrtConfigVersion.cmake
        DESTINATION ${SSRT_CMAKE_DIR})

# The ssrt command's bash completion and man page, which it writes itself from its own table of
# commands and flags (`ssrt completion bash`, `ssrt man`): after each link of the program, so
# that whatever builds `ssrt` (scripts/build.sh --render included) has both to install. Not in
# a cross build that cannot run what it builds.
if(TARGET ssrt_cli AND (NOT CMAKE_CROSSCOMPILING OR CMAKE_CROSSCOMPILING_EMULATOR))
    set(SSRT_COMPLETION_FILE ${CMAKE_BINARY_DIR}/share/bash-completion/completions/ssrt)
    set(SSRT_MAN_FILE ${CMAKE_BINARY_DIR}/share/man/man1/ssrt.1)
    foreach(doc "COMPLETION;completion bash" "MAN;man")
        list(GET doc 0 kind)
        list(GET doc 1 args)
        get_filename_component(dir ${SSRT_${kind}_FILE} DIRECTORY)
        add_custom_command(TARGET ssrt_cli POST_BUILD
                           COMMAND ${CMAKE_COMMAND} -E make_directory ${dir}
                           COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:ssrt_cli>
                                   "-DARGS=${args}" -DOUTPUT=${SSRT_${kind}_FILE}
                                   "-DEMULATOR=${CMAKE_CROSSCOMPILING_EMULATOR}"
                                   -P ${PROJECT_SOURCE_DIR}/cmake/run_to_file.cmake
                           COMMENT "ssrt ${args} > ${SSRT_${kind}_FILE}" VERBATIM)
    endforeach()
    install(FILES ${SSRT_COMPLETION_FILE}
            DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
    install(FILES ${SSRT_MAN_FILE} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()
