# Runs PROGRAM (under EMULATOR, where the build is a cross build's) with ARGS, a
# space-separated list, and writes what it prints to OUTPUT, failing on a non-zero status:
# how the build has ssrt write its own bash completion and man page (cmake/install.cmake).
#   cmake -DPROGRAM=... -DARGS="completion bash" -DOUTPUT=... [-DEMULATOR=...] -P run_to_file.cmake
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND ${EMULATOR} ${PROGRAM} ${args} OUTPUT_FILE ${OUTPUT}.tmp
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    file(REMOVE ${OUTPUT}.tmp)
    message(FATAL_ERROR "'${PROGRAM} ${ARGS}' failed (${status})")
endif()
file(RENAME ${OUTPUT}.tmp ${OUTPUT})
