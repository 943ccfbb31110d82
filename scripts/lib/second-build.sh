# Sourced by the scripts that make CI's second builds (test-clang.sh, test-arm.sh,
# test-sanitized.sh, test-tsan.sh): how those builds are configured, in one place.
#
# `second_build`: CMake options every second build takes:
#  - the compiler cache (scripts/lib/compiler-cache.sh);
#  - a unity build (CMAKE_UNITY_BUILD): CMake compiles each library's sources in batches of
#    eight, one compiler run per batch, so the headers every source includes (CLI11, oneTBB,
#    nlohmann/json, OpenImageIO, the standard library) are parsed once per batch, not once per
#    source (docs/ci.md, "Second builds", has the times). The test binary stays one source
#    per file (tests/CMakeLists.txt says why). The README's own build (scripts/build.sh) is
#    not a unity build: a developer's edit recompiles one file. The same bits either way,
#    which the clang and arm stages check against the gcc build.
#
# `configure_clang_sanitizer_build DIR OPTION...`: configures DIR for a sanitizer with clang 14,
# cut to what a report needs (test-sanitized.sh's header says why each cut): -O1
# -gline-tables-only, the scalar and AVX2 kernel families, no benchmarks; OPTIONs are the
# sanitizer's (-DSSRT_SANITIZE=ON, -DSSRT_SANITIZE_THREAD=ON, ...). A DIR configured with
# another compiler is made anew. SSRT_CLANG_CXX and SSRT_CLANG_CC choose the compiler.
source "$(dirname "${BASH_SOURCE[0]}")/compiler-cache.sh"
second_build=("${compiler_cache[@]}" -DCMAKE_UNITY_BUILD=ON)

configure_clang_sanitizer_build() {
    local dir=$1
    shift
    local cxx="${SSRT_CLANG_CXX:-clang++-14}" cc="${SSRT_CLANG_CC:-clang-14}"
    if [ -f "$dir/CMakeCache.txt" ] &&
        ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=.*$cxx\$" "$dir/CMakeCache.txt"; then
        rm -rf "$dir"
    fi
    CC="$cc" CXX="$cxx" cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG" \
        "-DSSRT_ISAS=scalar;avx2" -DSSRT_BUILD_PERF=OFF "${second_build[@]}" "$@" >/dev/null
}

# `test_files_for CASES`: the test sources holding a doctest case that CASES names (a -tc
# filter: comma-separated, `*` any text, `?` one character, any case), ';'-joined for
# -DSSRT_TEST_FILES, so a second build compiles only the tests it runs. A case's name may be on
# the line after `TEST_CASE(` and made of several string literals.
test_files_for() { # CASES
    find tests -name '*_test.cpp' | LC_ALL=C sort | perl -e '
        my @patterns = map {
            my $p = quotemeta($_);
            $p =~ s/\\\*/.*/g;
            $p =~ s/\\\?/./g;
            qr/^$p$/is
        } split /,/, $ARGV[0];
        my @files;
        while (my $file = <STDIN>) {
            chomp $file;
            open(my $in, "<", $file) or die "$file: $!";
            my $text = do { local $/; <$in> };
            my $wanted = 0;
            while ($text =~ /TEST_CASE\(\s*((?:"(?:[^"\\]|\\.)*"\s*)+)/g) {
                my $name = join("", $1 =~ /"((?:[^"\\]|\\.)*)"/g);
                $wanted = 1 if grep { $name =~ $_ } @patterns;
            }
            push @files, $file if $wanted;
        }
        print join(";", @files), "\n";' "$1"
}

# (same_cases' and run_cases' arguments after the label, FILTER... -- COMMAND..., into the
# caller's `filters` and `command` arrays)
_split_at_dashes() {
    filters=()
    while [ "$1" != -- ]; do
        filters+=("$1")
        shift
    done
    shift
    command=("$@")
}

# `same_cases LABEL FILTER... -- COMMAND...`: fails unless the test binary COMMAND lists the
# same cases for the doctest FILTERs (-tc=..., -tce=...) as scripts/test.sh's full binary
# (build/tests/ssrt_tests), where that is built: no case is lost to test_files_for.
same_cases() { # label, filter..., --, command...
    local label=$1 filters command
    _split_at_dashes "${@:2}"
    [ -x build/tests/ssrt_tests ] || return 0
    if ! diff <(build/tests/ssrt_tests "${filters[@]}" -ltc) <("${command[@]}" "${filters[@]}" -ltc) >&2; then
        echo "$label: the second build's tests match other cases than build/tests/ssrt_tests" >&2
        return 1
    fi
    echo "$label: $("${command[@]}" "${filters[@]}" -ltc | grep -c -v -e '^\[doctest\]' -e '^====') cases, as in the full test binary" >&2
}

# `run_cases LABEL FILTER... -- COMMAND...`: runs the doctest cases that the FILTERs match in
# processes of COMMAND (a test binary, or qemu-aarch64 and one), as many at once as there are
# cores (SSRT_BUILD_JOBS). Most cases spend most of their time on one thread (a 1-thread
# variant, the scalar oracle), and a sanitizer or an emulator makes them slow, so one process
# would leave the other cores idle. Every case runs, once; the output of each process that
# fails is printed, and the function fails once all have run.
run_cases() { # label, filter..., --, command...
    local label=$1 filters command
    _split_at_dashes "${@:2}"
    local count
    count=$("${command[@]}" "${filters[@]}" --count | sed -n 's/.*passing the current filters: \([0-9]*\).*/\1/p')
    if [ "${count:-0}" -eq 0 ]; then
        echo "$label: no test case matches ${filters[*]}" >&2
        return 1
    fi
    # At most 32 processes: one case each where there are few (slow cases under a sanitizer or
    # an emulator), consecutive runs of them where there are many (quick ones).
    local per=$(((count + 31) / 32)) jobs="${SSRT_BUILD_JOBS:-$(nproc)}" logs k pids=()
    local t0=$SECONDS
    logs=$(mktemp -d)
    for ((k = 1; k <= count; k += per)); do
        # (ordered by name, so that every process numbers the cases alike)
        { "${command[@]}" "${filters[@]}" --order-by=name --first="$k" --last="$((k + per - 1))" \
            >"$logs/$k.log" 2>&1 || echo "$k" >>"$logs/failed"; } &
        pids+=($!)
        # (oldest first: `wait -n` can miss a job that ended during a command substitution)
        if [ "${#pids[@]}" -ge "$jobs" ]; then
            wait "${pids[0]}"
            pids=("${pids[@]:1}")
        fi
    done
    wait
    if [ -s "$logs/failed" ]; then
        for k in $(sort -n "$logs/failed"); do cat "$logs/$k.log" >&2; done
        echo "$label: test cases FAILED, in $(wc -l <"$logs/failed") of the processes that ran" \
            "$count cases, $per each (output above)" >&2
        rm -rf "$logs"
        return 1
    fi
    echo "$label: $count test cases passed, $jobs at a time, in $((SECONDS - t0)) s" >&2
    rm -rf "$logs"
}
