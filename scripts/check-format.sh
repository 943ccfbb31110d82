#!/usr/bin/env bash
# Fails (exit 1, listing the files) when clang-format 14 would change any tracked *.cpp or *.h
# (.clang-format; STYLE.md). Generated files are left as their generator writes them: they are
# listed once, in kGenerated below. Cheap, so CI runs it first.
#
#   scripts/check-format.sh            # check
#   clang-format -i FILE...            # fix what it lists
set -euo pipefail
cd "$(dirname "$0")/.."

# Written by a generator (see each file's first line), never formatted by hand.
readonly kGenerated=(
    scenes/data/bunny_mesh.cpp   # scripts/import-bunny.sh
    shading/energy_tables_data.h # ssrt_gen_energy_tables
)

format="${CLANG_FORMAT:-clang-format-14}"
command -v "$format" >/dev/null || format=clang-format
if ! "$format" --version | grep -q 'version 14\.'; then
    echo "check-format: needs clang-format 14 (apt-get install clang-format-14); found:" \
         "$("$format" --version 2>/dev/null || echo none)" >&2
    exit 2
fi

excludes=()
for f in "${kGenerated[@]}"; do excludes+=(":(exclude)$f"); done

# One clang-format run over every file; --dry-run -Werror names each file it would change
# ("FILE:LINE:COL: error: code should be clang-formatted") and exits non-zero.
status=0
report=$(git ls-files -z -- '*.cpp' '*.h' "${excludes[@]}" |
         xargs -0 "$format" --style=file --dry-run -Werror 2>&1) || status=$?
mapfile -t bad < <(sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' \
                   <<<"$report" | sort -u)
if [ $status -ne 0 ] && [ ${#bad[@]} -eq 0 ]; then
    echo "check-format: $format failed:" >&2
    echo "$report" >&2
    exit 2
fi

if [ ${#bad[@]} -ne 0 ]; then
    echo "check-format: clang-format 14 would change ${#bad[@]} file(s):" >&2
    printf '  %s\n' "${bad[@]}" >&2
    echo "fix with: clang-format -i ${bad[*]}" >&2
    exit 1
fi
echo "check-format: every tracked .cpp and .h is formatted"
