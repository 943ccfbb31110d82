#!/usr/bin/env bash
# The renderer's threads under ThreadSanitizer (issue 47): every test case that compares bits
# across thread counts (its name says "thread"), 8 renderers on 8 threads at once and the
# refusal of a frame or history two render calls share (tests/renderer/concurrent_render_test.cpp),
# `ssrt render --frames` with its history at 1, 2 and 8 threads (the same bytes), and the Python
# module's threaded tests. Any report fails (TSan's exit status 66). Builds in build-tsan/; CI
# runs it after scripts/test-sanitized.sh.
#
# ssrt's threads are oneTBB's, and Debian's libtbb is not instrumented: TSan would not see the
# synchronisation inside it (a task's spawn and its wait) and would report the tiles' writes
# and the reads after the loop as races. So this builds Debian 12's own oneTBB (the package's
# source and patches, checksums pinned below) with TBB_SANITIZE=thread, oneTBB's own switch, and
# links against it. The build (about a minute) is kept outside the
# checkout (SSRT_TSAN_TBB_CACHE, default ~/.cache/ssrt-tsan-tbb), keyed by the recipe below, so a
# second run reuses it. Embree and OpenImageIO stay Debian's (uninstrumented: TSan checks none
# of their memory accesses); Embree's libtbb.so.12 is then this one, already loaded.
# Suppressions only for what Embree's uninstrumented waits hide (tests/tsan.supp says each
# one's why); none for ssrt.
#
# Python is not instrumented, and clang 14's TSan run-time cannot be preloaded into it (it
# crashes in libstdc++'s start-up), so the module's tests run under a two-line launcher built
# here with TSan (build-tsan/python3-tsan: Debian's libpython3.11 behind an instrumented main()),
# which starts the run-time before the interpreter and gives the module its symbols.
#
# The build is cut as the sanitized stage's is (scripts/test-sanitized.sh says why; both are
# configured by scripts/lib/second-build.sh): clang 14, -O1 -gline-tables-only, the scalar and
# AVX2 kernel families, the libraries as a unity build, and here only the test files whose
# cases run (SSRT_TEST_FILES), `ssrt` and the module.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
source scripts/lib/second-build.sh
cxx="${SSRT_CLANG_CXX:-clang++-14}"
cc="${SSRT_CLANG_CC:-clang-14}"
jobs="${SSRT_BUILD_JOBS:-$(nproc)}"

# --- oneTBB with ThreadSanitizer ----------------------------------------------------------
tbb_debian=2021.8.0-2+deb12u1 # libtbb-dev in Debian 12
tbb_pool="${SSRT_DEBIAN_MIRROR:-http://deb.debian.org/debian}/pool/main/o/onetbb"
tbb_files=(
    "onetbb_2021.8.0.orig.tar.xz 7e9111b8bb59c8800bf6d0b06afe7b0891937443d2dae1ee1101c8e2ede6a7ef"
    "onetbb_${tbb_debian}.debian.tar.xz b83a270205b38cdf66972fa1467c3e29493b88b92ecacf4f3672e87d67199df5"
)

download() { # url, file
    if command -v curl >/dev/null; then curl -fsSL -o "$2" "$1"; else wget -q -O "$2" "$1"; fi
}

build_tbb() { # prefix
    local work entry name sum src patch
    work=$(mktemp -d)
    for entry in "${tbb_files[@]}"; do
        read -r name sum <<<"$entry"
        download "$tbb_pool/$name" "$work/$name" || {
            echo "test-tsan: cannot download $tbb_pool/$name (oneTBB's source)" >&2
            return 1
        }
        echo "$sum  $work/$name" | sha256sum --quiet -c - || {
            echo "test-tsan: $tbb_pool/$name: not the file Debian 12 ships (SHA-256 differs)" >&2
            return 1
        }
    done
    tar -xf "$work/${tbb_files[0]%% *}" -C "$work"
    src=$(echo "$work"/oneTBB-*)
    tar -xf "$work/${tbb_files[1]%% *}" -C "$src"
    while read -r patch; do
        [ -n "$patch" ] && patch -s -p1 -d "$src" <"$src/debian/patches/$patch"
    done <"$src/debian/patches/series"
    CC="$cc" CXX="$cxx" cmake -S "$src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG" -DTBB_SANITIZE=thread \
        -DTBB_TEST=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF \
        -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON -DCMAKE_INSTALL_PREFIX="$1" >/dev/null
    cmake --build "$work/build" --parallel "$jobs" >/dev/null
    cmake --install "$work/build" >/dev/null
    rm -rf "$work"
}

tbb_key=$( (declare -f build_tbb && printf '%s\n' "${tbb_files[@]}" && "$cxx" --version) |
    sha256sum | cut -c1-12)
tbb_prefix="${SSRT_TSAN_TBB_CACHE:-$HOME/.cache/ssrt-tsan-tbb}/$tbb_debian-$tbb_key"
if [ ! -d "$tbb_prefix" ]; then
    t0=$SECONDS
    mkdir -p "$(dirname "$tbb_prefix")"
    rm -rf "$tbb_prefix.part"
    build_tbb "$tbb_prefix.part"
    mv -T "$tbb_prefix.part" "$tbb_prefix" # whole or not at all
    echo "test-tsan: built oneTBB $tbb_debian with ThreadSanitizer in $((SECONDS - t0)) s" >&2
fi

# --- ssrt with ThreadSanitizer --------------------------------------------------------------
# The cases that run (doctest's filter); only the test files that hold them are compiled.
cases='*thread*,concurrent render:*'
t0=$SECONDS
configure_clang_sanitizer_build build-tsan -DSSRT_SANITIZE_THREAD=ON -DSSRT_BUILD_PYTHON=ON \
    "-DSSRT_TEST_FILES=$(test_files_for "$cases")" -DTBB_DIR="$tbb_prefix/lib/cmake/TBB"
cmake --build build-tsan --target ssrt_tests ssrt_cli ssrt_python --parallel "$jobs"
python_include=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_paths()["include"])')
python_lib=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_config_var("LDVERSION"))')
echo '#include <Python.h>
int main(int argc, char** argv) { return Py_BytesMain(argc, argv); }' |
    "$cc" -fsanitize=thread -O1 -I"$python_include" -x c - -o build-tsan/python3-tsan \
        -lpython"$python_lib"
echo "test-tsan: built build-tsan/ in $((SECONDS - t0)) s" >&2

# Every binary must load the instrumented oneTBB (a system one would bring false reports).
for bin in build-tsan/tests/ssrt_tests build-tsan/ssrt; do
    libs=$(ldd "$bin")
    grep -q "libtbb.so.12 => $tbb_prefix/" <<<"$libs" || {
        echo "test-tsan: $bin does not load the instrumented oneTBB in $tbb_prefix" >&2
        exit 1
    }
done

same_cases test-tsan -tc="$cases" -- ./build-tsan/tests/ssrt_tests

# halt_on_error: the first report ends the run (exit 66), so a race cannot pass unnoticed.
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$PWD/tests/tsan.supp"
t0=$SECONDS
# The thread counts over 1 (tests/thread_counts.h): one thread cannot race.
SSRT_TEST_THREADS=parallel run_cases test-tsan -tc="$cases" -- ./build-tsan/tests/ssrt_tests
echo "test-tsan: the threaded test cases took $((SECONDS - t0)) s" >&2

# A sequence with its history (the denoiser's and the reprojected colour's) at 1, 2 and 8
# threads: the same bytes.
t0=$SECONDS
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for threads in 1 2 8; do
    ./build-tsan/ssrt render --scene cornell --width 160 --height 90 --frames 4 \
        --threads "$threads" --quiet -o "$out/t$threads.exr"
done
for frame in "$out"/t1_*.exr; do
    name=$(basename "$frame")
    for threads in 2 8; do
        cmp "$frame" "$out/t$threads${name#t1}"
    done
done
echo "test-tsan: ssrt render --frames 4 at 1, 2 and 8 threads took $((SECONDS - t0)) s" >&2

t0=$SECONDS
PYTHONPATH=build-tsan/python SSRT_CLI=build-tsan/ssrt ./build-tsan/python3-tsan -m pytest -q \
    -p no:cacheprovider python/tests/test_concurrent.py python/tests/test_gil.py
echo "test-tsan: the Python module's threaded tests took $((SECONDS - t0)) s" >&2
