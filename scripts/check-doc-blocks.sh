#!/usr/bin/env bash
# Runs the documentation's runnable blocks and checks the flags and help sections it names
# against the program, so that README.md and docs/*.md say only what ssrt does.
#
#   scripts/check-doc-blocks.sh [BUILD_DIR]     # default build/ (scripts/test.sh runs it)
#   scripts/check-doc-blocks.sh BUILD_DIR FILE.md ...   # only these files
#
# 1. Runnable blocks. A fenced block is runnable when the line just before its opening fence
#    is `<!-- runnable -->` (indented as the fence may be, in a list) and the fence is ```sh or
#    ```python; a line that starts as a marker but is not one is an error. The blocks of one file run in order, in one temporary folder of their own that stands in for the
#    repository's root: every top-level entry of the checkout is linked into it (so
#    `examples/shots/...` and `perf/plot.py` resolve), `build` is linked to BUILD_DIR, and
#    whatever a block writes stays in the temporary folder. A sh block runs under
#    `bash -euo pipefail`, traced, a python block under `/usr/bin/python3` with
#    PYTHONPATH=build/python, as the docs say to run them; BUILD_DIR is first on PATH;
#    SSRT_CACHE_DIR is a fresh folder (the user's reference cache is left alone). Any
#    non-zero exit, or a block over 120 s, fails. Blocks are written at small sizes so the
#    whole check takes well under a minute.
# 2. Flags. Every `--flag` the files name must be in the help of `ssrt` or one of its
#    subcommands, or in the short list below of other programs' flags the docs quote.
# 3. Help sections. A mention of `ssrt COMMAND --help`, "SECTION" must name a section
#    (a "SECTION:" line) of that command's help.
# 4. Links. Every Markdown link is a relative path to something in the checkout: no URL.
# Exit 0 when everything passes, 1 otherwise (each failure named), 2 for a bad invocation.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
[ $# -gt 0 ] && shift
build="$(cd "$build" 2>/dev/null && pwd)" || { echo "check-doc-blocks: no build folder '$build'" >&2; exit 2; }
ssrt="$build/ssrt"
[ -x "$ssrt" ] || { echo "check-doc-blocks: no $ssrt (build it: scripts/build.sh)" >&2; exit 2; }
if [ $# -gt 0 ]; then
    files=("$@")
else
    files=("$root/README.md" "$root"/docs/*.md)
fi

# Other programs' flags that the docs quote (each with its program), not ssrt's.
readonly kOtherFlags=(
    --array --cpus-per-task --wait --wrap --signal        # sbatch
    --install --prefix --component                        # cmake
    --variant                                             # debootstrap
    --no-install-recommends                               # apt-get
    --add-architecture                                    # dpkg
    --render                                              # scripts/build.sh
    --x --y                                               # perf/plot.py
    --untimed                                             # perf/soak.sh
    --prepare                                             # scripts/test-fresh.sh
    --widht                                               # a misspelling shown as an error
)

tmp="$(mktemp -d "${TMPDIR:-/tmp}/ssrt-doc-blocks.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "check-doc-blocks: FAIL: $*" >&2; failures=$((failures + 1)); }
rel() { echo "${1#"$root"/}"; }

# --- 2 and 3: flags and help sections -------------------------------------------------------
"$ssrt" --help >"$tmp/help.top"
mapfile -t commands < <(sed -n '/^Subcommands:/,/^$/p' "$tmp/help.top" | awk 'NR > 1 && /^  [a-z]/ { print $1 }')
[ ${#commands[@]} -gt 0 ] || { echo "check-doc-blocks: no commands in 'ssrt --help'" >&2; exit 2; }
for c in "${commands[@]}"; do "$ssrt" "$c" --help >"$tmp/help.$c"; done
grep -ohE -- '(^|[^A-Za-z0-9_-])--[a-z][a-z0-9-]*' "$tmp"/help.* | grep -oE -- '--[a-z0-9-]+' \
    | sort -u >"$tmp/known-flags"
printf '%s\n' "${kOtherFlags[@]}" >>"$tmp/known-flags"
flags_checked=0
for f in "${files[@]}"; do
    # Every --flag (a word such as "well--known" is not one).
    while IFS=: read -r line flag; do
        flags_checked=$((flags_checked + 1))
        grep -qxF -- "$flag" "$tmp/known-flags" ||
            fail "$(rel "$f"):$line: $flag is not a flag of ssrt (no 'ssrt ... --help' lists it)"
    done < <(grep -noE -- '(^|[^A-Za-z0-9_-])--[a-z][a-z0-9-]*' "$f" \
        | sed -E 's/^([0-9]+):.*(--[a-z0-9-]+)$/\1:\2/' | grep -v -- ':--$' || true)
    while IFS= read -r mention; do
        line="${mention%%:*}"
        command="$(sed -E 's/.*ssrt ([a-z]+) --help.*/\1/' <<<"$mention")"
        section="$(sed -E 's/.*--help`?, "([^"]+)".*/\1/' <<<"$mention")"
        if [ ! -f "$tmp/help.$command" ]; then
            fail "$(rel "$f"):$line: 'ssrt $command' is not a command"
        elif ! grep -qxF -- "$section:" "$tmp/help.$command"; then
            fail "$(rel "$f"):$line: 'ssrt $command --help' has no section \"$section\""
        fi
    done < <(grep -noE -- 'ssrt [a-z]+ --help`?, "[^"]+"' "$f" || true)
done

# --- 4: links ------------------------------------------------------------------------------
# Every Markdown link stays in the repository: a relative path to a file or folder that exists
# (an anchor after '#' is not checked), never a URL.
links_checked=0
for f in "${files[@]}"; do
    while IFS=: read -r line target; do
        links_checked=$((links_checked + 1))
        target="${target#](}"
        target="${target%)}"
        path="${target%%#*}"
        case "$target" in
        *://* | mailto:*) fail "$(rel "$f"):$line: the link $target leaves the repository" ;;
        '#'*) ;;
        *) [ -e "$(dirname "$f")/$path" ] ||
            fail "$(rel "$f"):$line: the link $target names no file of the repository" ;;
        esac
    done < <(grep -noE -- '\]\([^) ]+\)' "$f" || true)
done

# --- 1: runnable blocks ----------------------------------------------------------------------
# Splits FILE's runnable blocks into DIR/NNN.sh or DIR/NNN.py, padded with empty lines so that
# a line of a block has its line number in FILE (a trace or a traceback names FILE's lines),
# and DIR/NNN.where holding "FILE:LINE" of the opening fence.
extract() { # file, dir
    awk -v dir="$2" -v name="$(rel "$1")" '
        function fail_at(msg) { printf "%s:%d: %s\n", name, NR, msg > "/dev/stderr"; bad = 1 }
        inblock {
            if ($0 ~ /^[ \t]*```[ \t]*$/) { inblock = 0; close(out); next }
            line = $0
            if (substr(line, 1, indent) ~ /^[ ]*$/) line = substr(line, indent + 1)
            print line > out; next
        }
        armed {
            armed = 0
            if ($0 ~ /^[ ]*```sh[ \t]*$/) ext = "sh"
            else if ($0 ~ /^[ ]*```python[ \t]*$/) ext = "py"
            else { fail_at("<!-- runnable --> must be followed by a ```sh or ```python fence"); next }
            match($0, /^[ ]*/); indent = RLENGTH
            n++
            out = sprintf("%s/%03d.%s", dir, n, ext)
            printf "%s:%d\n", name, NR > sprintf("%s/%03d.where", dir, n)
            # A sh block traces itself (bash ignores PS4 from the environment when run as root).
            if (ext == "sh") printf "PS4=\047+ %s:$LINENO: \047; set -x\n", name > out
            else printf "\n" > out
            for (i = 1; i < NR; i++) printf "\n" > out
            inblock = 1; next
        }
        /^[ ]*<!-- runnable -->[ \t]*$/ { armed = 1; next }
        /^[ ]*<!-- *runnable/ { fail_at("a runnable marker must be a line of its own: <!-- runnable -->") }
        END {
            if (inblock) fail_at("a runnable block is not closed")
            if (armed) fail_at("<!-- runnable --> at the end of the file")
            exit bad
        }' "$1"
}

blocks_run=0
t0=$SECONDS
for f in "${files[@]}"; do
    name="$(rel "$f")"
    blocks="$tmp/blocks/${name//\//_}"
    mkdir -p "$blocks"
    extract "$f" "$blocks" || { fail "$name: malformed runnable block"; continue; }
    compgen -G "$blocks/*.where" >/dev/null || continue
    work="$tmp/work/${name//\//_}"
    mkdir -p "$work" "$tmp/cache"
    for entry in "$root"/*; do
        [ "$(basename "$entry")" = build ] || ln -s "$entry" "$work/$(basename "$entry")"
    done
    ln -s "$build" "$work/build"
    for where_file in "$blocks"/*.where; do
        block="${where_file%.where}.sh"
        [ -f "$block" ] || block="${where_file%.where}.py"
        where="$(cat "$where_file")"
        blocks_run=$((blocks_run + 1))
        t_block=$SECONDS
        status=0
        case "$block" in
        *.sh)
            # Traced: a failure's last lines show the command that failed, with its line in FILE.
            (cd "$work" && PATH="$build:$PATH" SSRT_CACHE_DIR="$tmp/cache" \
                timeout 120 bash -euo pipefail "$block") >"$block.log" 2>&1 || status=$?
            ;;
        *.py)
            if [ ! -f "$build/python/ssrt/__init__.py" ]; then
                echo "no $build/python/ssrt: the full build (scripts/build.sh) makes it" >"$block.log"
                status=1
            else
                (cd "$work" && PATH="$build:$PATH" SSRT_CACHE_DIR="$tmp/cache" \
                    PYTHONPATH=build/python PYTHONDONTWRITEBYTECODE=1 \
                    timeout 120 /usr/bin/python3 "$block") \
                    >"$block.log" 2>&1 || status=$?
            fi
            ;;
        esac
        if [ $status -ne 0 ]; then
            fail "$where: the block exited $status after $((SECONDS - t_block)) s; its last lines:"
            tail -n 15 "$block.log" | sed 's/^/    /' >&2
        else
            echo "check-doc-blocks: ok   $where ($((SECONDS - t_block)) s)"
        fi
    done
done

echo "check-doc-blocks: ${#files[@]} files, $flags_checked flag mentions and $links_checked links checked," \
    "$blocks_run blocks run in $((SECONDS - t0)) s, $failures failed"
[ $failures -eq 0 ]
