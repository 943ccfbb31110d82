# The sanitizers' run-time options, for the sanitized tests and the fuzz targets alike
# (sourced by scripts/test-sanitized.sh and scripts/fuzz.sh).
# tinygltf is a system library built without ASan: containers it fills trip ASan's
# container-overflow annotations falsely, so that one check is off.
export ASAN_OPTIONS=detect_container_overflow=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# One known leak inside OpenImageIO on corrupt PNGs (see the file).
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp
