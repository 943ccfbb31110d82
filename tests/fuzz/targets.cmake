# The libFuzzer targets (tests/fuzz/README.md), in the sanitized build only: clang 14 with
# SSRT_SANITIZE (scripts/test-sanitized.sh builds them and replays the committed corpora,
# scripts/fuzz.sh runs a campaign). Included by the top-level CMakeLists.txt, whose directory
# the libraries belong to.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT SSRT_SANITIZE)
    message(FATAL_ERROR "SSRT_BUILD_FUZZ needs clang (libFuzzer) and SSRT_SANITIZE=ON")
endif()

# Coverage for what parses untrusted input, so that libFuzzer sees which branches an input
# reached there; the kernels are left uninstrumented (their objects stay the sanitized
# build's, and the parsers are what is fuzzed).
foreach(parser ssrt_io ssrt_shot ssrt_gltf ssrt_cli_lib)
    target_compile_options(${parser} PRIVATE -fsanitize=fuzzer-no-link)
endforeach()

# FLIP's filters are arithmetic over every pixel, not parsing: their comparisons, traced for
# libFuzzer, took most of a diff_fuzz run (an image of any size is filtered with kernels tens of
# taps wide) and guide the fuzzer nowhere. They keep the sanitizers.
set_source_files_properties(io/flip.cpp PROPERTIES COMPILE_OPTIONS
                            "-fno-sanitize-coverage=trace-cmp,inline-8bit-counters,pc-table")

set(SSRT_FUZZ_TARGETS cli_fuzz diff_fuzz gltf_fuzz merge_fuzz shot_fuzz sky_image_fuzz
                      suite_fuzz texture_fuzz)
foreach(target ${SSRT_FUZZ_TARGETS})
    add_executable(${target} EXCLUDE_FROM_ALL tests/fuzz/${target}.cpp)
    set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer)
    target_link_options(${target} PRIVATE -fsanitize=fuzzer)
    target_link_libraries(${target} PRIVATE ssrt_cli_lib)
endforeach()
add_custom_target(ssrt_fuzz DEPENDS ${SSRT_FUZZ_TARGETS})
