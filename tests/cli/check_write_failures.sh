#!/usr/bin/env bash
# Issue 47's full disks and unwritable places: a write that fails part-way (a small tmpfs
# filled, `ulimit -f`), a read-only folder and a path that is a folder end with exit 3 and one
# line naming the file and the cause, nothing partial under the target's name, no temporary
# left, and the frames written before kept whole (byte-identical to an unhindered run's).
# Mounting needs root: where it is not permitted, those parts say SKIPPED and the rest runs.
# Usage: check_write_failures.sh SSRT (ctest passes it).
set -uo pipefail
ssrt="$1"
dir=$(mktemp -d)
mounts=()
cleanup() {
    for m in "${mounts[@]}"; do umount "$m" 2>/dev/null; done
    rm -rf "$dir"
}
trap cleanup EXIT
size=(--scene cornell --width 320 --height 180)

fail() {
    echo "check_write_failures: FAIL: $*" >&2
    exit 1
}
say() { echo "check_write_failures: $*" >&2; }

# expect NAME PATTERN COMMAND...: exit 3, stderr's only error line matches PATTERN.
expect() {
    local name="$1" pattern="$2"
    shift 2
    "$@" >"$dir/$name.out" 2>"$dir/$name.err"
    local code=$?
    [ "$code" = 3 ] || fail "$name: exit $code, not 3 ($(tail -n 2 "$dir/$name.err"))"
    local errors
    errors=$(grep -c "^ssrt: error:" "$dir/$name.err")
    [ "$errors" = 1 ] || fail "$name: $errors error lines: $(cat "$dir/$name.err")"
    grep -q "$pattern" "$dir/$name.err" || fail "$name: no '$pattern' in $(cat "$dir/$name.err")"
    say "$name: $(grep "^ssrt: error:" "$dir/$name.err")"
}
no_temporaries() {
    local left
    left=$(find "$1" -name '.*.tmp-*' -o -name '*.tmp')
    [ -z "$left" ] || fail "temporaries left: $left"
}
# mount_tmpfs FOLDER OPTIONS: a tmpfs there, or 1 where this machine does not allow it.
mount_tmpfs() {
    mkdir -p "$1"
    mount -t tmpfs -o "$2" tmpfs "$1" 2>/dev/null || return 1
    mounts+=("$1")
}

# The frames unhindered, to hold the kept ones against and to size the filesystems by.
mkdir -p "$dir/whole"
"$ssrt" render "${size[@]}" --frames 6 -q -o "$dir/whole/f.png" || fail "the unhindered run"
frame_bytes=$(stat -c %s "$dir/whole/f_0000.png")
kept_whole() {  # kept_whole FOLDER N: frames 0..N-1 there, each the unhindered one
    for i in $(seq 0 $(($2 - 1))); do
        cmp -s "$1/f_000$i.png" "$dir/whole/f_000$i.png" || fail "$1/f_000$i.png not kept whole"
    done
}

# --- A full disk: a tmpfs that holds about 3.5 frames, so the 4th write fails part-way -------
if mount_tmpfs "$dir/full" "size=$((frame_bytes * 7 / 2 / 4096 * 4096 + 4096))"; then
    expect full "cannot write '$dir/full/f_0003.png': No space left on device$" \
        "$ssrt" render "${size[@]}" --frames 6 -o "$dir/full/f.png"
    kept_whole "$dir/full" 3
    [ ! -e "$dir/full/f_0003.png" ] || fail "full: a partial f_0003.png"
    no_temporaries "$dir/full"
    # A text file (merge's CSV, as sweep's and check's reports are written) on the disk filled.
    dd if=/dev/zero of="$dir/full/filler" bs=4096 2>/dev/null
    expect full-exr "cannot write '$dir/full/x.exr': Cannot open image file. No space left on device.$" \
        "$ssrt" render "${size[@]}" -o "$dir/full/x.exr"
    printf 'setting,x\n0,a\n' >"$dir/s.shard-1-of-2.csv"
    printf 'setting,x\n1,b\n' >"$dir/s.shard-2-of-2.csv"
    expect full-csv "cannot write '$dir/full/s.csv': No space left on device$" \
        "$ssrt" merge -o "$dir/full/s.csv" "$dir/s.shard-1-of-2.csv" "$dir/s.shard-2-of-2.csv"
    [ ! -e "$dir/full/s.csv" ] || fail "full-csv: a partial s.csv"
    no_temporaries "$dir/full"
else
    say "SKIPPED: the full tmpfs (mount is not permitted here)"
fi

# --- `ulimit -f`: every write over the limit fails with EFBIG (ssrt ignores SIGXFSZ) --------
mkdir -p "$dir/fsize"
expect fsize "cannot write '$dir/fsize/f_0000.png': File too large$" \
    bash -c "ulimit -f $((frame_bytes / 2048)) && exec \"\$0\" \"\$@\"" \
    "$ssrt" render "${size[@]}" --frames 3 -o "$dir/fsize/f.png"
expect fsize-exr "cannot write '$dir/fsize/x.exr': Failed to write pixel data to image file. File too large.$" \
    bash -c "ulimit -f $((frame_bytes / 2048)) && exec \"\$0\" \"\$@\"" \
    "$ssrt" render "${size[@]}" -o "$dir/fsize/x.exr"
[ -z "$(ls -A "$dir/fsize")" ] || fail "fsize: left $(ls -A "$dir/fsize")"

# --- A folder where a frame's file goes: the frames before it kept --------------------------
mkdir -p "$dir/folder/f_0002.png"
expect folder "cannot write '$dir/folder/f_0002.png': it is a directory$" \
    "$ssrt" render "${size[@]}" --frames 6 -o "$dir/folder/f.png"
kept_whole "$dir/folder" 2
no_temporaries "$dir/folder"
mkdir -p "$dir/ref.exr"
expect reference-folder "cannot write '$dir/ref.exr': it is a directory$" \
    "$ssrt" reference "${size[@]}" --reference-spp 1 --no-cache -o "$dir/ref.exr"
# check's report: its cases are rendered, then report.html cannot be written.
mkdir -p "$dir/suite/out/report.html"
cat >"$dir/suite/suite.json" <<'EOF'
{"cases": [{"name": "a", "render": ["--width", "32", "--height", "18"],
            "reference": "golden/a.png"}]}
EOF
expect report-folder "cannot write '$dir/suite/out/report.html': it is a directory$" \
    "$ssrt" check "$dir/suite/suite.json" -o "$dir/suite/out"
no_temporaries "$dir/suite"

# --- A read-only folder: a read-only tmpfs as root (permissions do not stop root), else a
# folder without write permission ------------------------------------------------------------
if [ "$(id -u)" = 0 ]; then
    mount_tmpfs "$dir/ro" "ro,size=64k" || {
        say "SKIPPED: the read-only folder (mount is not permitted here)"
        rmdir "$dir/ro"
    }
else
    mkdir -p "$dir/ro" && chmod 555 "$dir/ro"
fi
if [ -d "$dir/ro" ]; then
    cause="(\(Read-only file system\|Permission denied\))$"
    expect ro-render "cannot write '$dir/ro/f.png': cannot create a file in '$dir/ro' $cause" \
        "$ssrt" render "${size[@]}" -o "$dir/ro/f.png"
    expect ro-reference "cannot write '$dir/ro/r.exr': cannot create a file in '$dir/ro' $cause" \
        "$ssrt" reference "${size[@]}" --reference-spp 1 --no-cache -o "$dir/ro/r.exr"
    [ -z "$(ls -A "$dir/ro")" ] || fail "ro: left $(ls -A "$dir/ro")"
fi
say "all passed"
