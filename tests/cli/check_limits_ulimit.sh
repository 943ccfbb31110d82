#!/usr/bin/env bash
# Under `ulimit -v 4000000` (4 GB of address space), issue 33's limits still end in one line
# naming the file or the flags and the limit, exit 3, nothing written: the 68-byte PNG that
# claims 60000 x 60000 pixels as an environment image, and an 8192 x 8192 frame. Then what gets
# past those checks (issue 47): under `ulimit -v 1500000` a 16384 x 8192 environment image
# (within the limits, a 130 kB PNG made here: 1.6 GB as floats) runs out of memory while it is
# read, which is one line too, exit 3, never an abort.
# Usage: check_limits_ulimit.sh SSRT SOURCE_DIR (ctest passes both).
set -uo pipefail
ssrt="$1"
png="$2/tests/io/data/oversized/big.png"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf '{"scene": "spheres", "environment": {"type": "image", "file": "%s"}}' "$png" \
    >"$dir/shot.json"
fail() { echo "check_limits_ulimit: $*" >&2; exit 1; }
limit=4000000
expect() {  # expect PATTERN ARGS...: exit 3, one line matching PATTERN, no output file
    local pattern="$1"
    shift
    (ulimit -v "$limit" && "$ssrt" "$@" -o "$dir/out.png" 2>"$dir/err")
    local code=$?
    [ "$code" = 3 ] || fail "exit $code, not 3: $* ($(cat "$dir/err"))"
    [ "$(wc -l <"$dir/err")" = 1 ] || fail "not one line: $(cat "$dir/err")"
    grep -q "$pattern" "$dir/err" || fail "no '$pattern' in: $(cat "$dir/err")"
    [ ! -e "$dir/out.png" ] || fail "out.png written: $*"
    cat "$dir/err"
}
expect "^ssrt: error: cannot read '$png': the image is 60000 x 60000 pixels, over the limit of 134217728 pixels" \
    render --shot "$dir/shot.json"
expect "^ssrt: error: --width, --height: a 8192 x 8192 frame needs about .* this process may use (ulimit -v)$" \
    render --width 8192 --height 8192

# A grey PNG of 16384 x 8192 zeros, the largest size the limits let through.
/usr/bin/python3 - "$dir/sky.png" <<'PY' || fail "cannot make the 16384 x 8192 PNG"
import struct, sys, zlib
width, height = 16384, 8192
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
z = zlib.compressobj(9)
pixels = b"".join(z.compress(bytes(width + 1)) for _ in range(height)) + z.flush()
header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)  # 8-bit grey
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
                              chunk(b"IDAT", pixels) + chunk(b"IEND", b""))
PY
printf '{"scene": "spheres", "environment": {"type": "image", "file": "%s"}}' "$dir/sky.png" \
    >"$dir/sky.json"
limit=1500000
expect "^ssrt: error: out of memory: an allocation failed; this process may use about 1\.[0-9] GB (ulimit -v)$" \
    render --shot "$dir/sky.json" --width 64 --height 36
