# The Python module `ssrt` (python/): pybind11 over the library, built for Debian's
# interpreter (/usr/bin/python3 with python3-numpy, not whatever `python3` is first on PATH).
# build/python/ is an importable package folder (PYTHONPATH=build/python); `cmake --install`
# puts the same folder into the interpreter's site-packages (SSRT_PYTHON_INSTALL_DIR), so
# `import ssrt` works without PYTHONPATH. Its .pyi stubs are written at build time from the
# built module (python/gen_stubs.py), so they say what the module holds.
if(NOT TARGET ssrt_cli_lib)
    message(FATAL_ERROR "SSRT_BUILD_PYTHON needs SSRT_BUILD_CLI or SSRT_BUILD_TESTS: the module "
                        "loads scenes and shots through the CLI's code (cli/options.h)")
endif()
set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The interpreter the module is built for")
set(PYBIND11_FINDPYTHON ON)
find_package(Python 3.11 REQUIRED COMPONENTS Interpreter Development.Module)
find_package(pybind11 2.10 CONFIG REQUIRED)

set(SSRT_PYTHON_DIR ${CMAKE_BINARY_DIR}/python)
# NO_EXTRAS: no link-time optimisation (the binding's inlined copies of the library's inline
# code are then compiled exactly as the library's) and no strip.
pybind11_add_module(ssrt_python MODULE NO_EXTRAS
    ${CMAKE_CURRENT_LIST_DIR}/module.cpp ${CMAKE_CURRENT_LIST_DIR}/settings.cpp
    ${CMAKE_CURRENT_LIST_DIR}/scenes.cpp ${CMAKE_CURRENT_LIST_DIR}/frames.cpp
    ${CMAKE_CURRENT_LIST_DIR}/files.cpp)
set_target_properties(ssrt_python PROPERTIES OUTPUT_NAME _ssrt
                                             LIBRARY_OUTPUT_DIRECTORY ${SSRT_PYTHON_DIR}/ssrt)
target_link_libraries(ssrt_python PRIVATE ssrt_cli_lib)
# The package's Python files beside the extension, and the stubs from the built module (-P:
# not python/ssrt, the sources beside the script, which lack the extension).
set(ssrt_python_files __init__.py py.typed)
foreach(f ${ssrt_python_files})
    configure_file(${CMAKE_CURRENT_LIST_DIR}/ssrt/${f} ${SSRT_PYTHON_DIR}/ssrt/${f} COPYONLY)
endforeach()
set(ssrt_python_stubs ${SSRT_PYTHON_DIR}/ssrt/_ssrt.pyi ${SSRT_PYTHON_DIR}/ssrt/__init__.pyi)
add_custom_command(OUTPUT ${ssrt_python_stubs}
    COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${SSRT_PYTHON_DIR}
            ${Python_EXECUTABLE} -P ${CMAKE_CURRENT_LIST_DIR}/gen_stubs.py ${SSRT_PYTHON_DIR}/ssrt
    DEPENDS ssrt_python ${CMAKE_CURRENT_LIST_DIR}/gen_stubs.py
    COMMENT "Writing the ssrt module's .pyi stubs")
add_custom_target(ssrt_python_stubs ALL DEPENDS ${ssrt_python_stubs})

execute_process(COMMAND ${Python_EXECUTABLE} -c "import sysconfig; print(sysconfig.get_path('platlib'))"
                OUTPUT_VARIABLE ssrt_site OUTPUT_STRIP_TRAILING_WHITESPACE)
set(SSRT_PYTHON_INSTALL_DIR ${ssrt_site} CACHE PATH
    "Where `cmake --install` puts the ssrt package (the interpreter's site-packages)")
install(DIRECTORY ${SSRT_PYTHON_DIR}/ssrt DESTINATION ${SSRT_PYTHON_INSTALL_DIR}
        COMPONENT python EXCLUDE_FROM_ALL)
