#!/usr/bin/env bash
# The HTML report of `ssrt check` in a real browser: Debian's headless Chromium loads it with no
# console message, no script error and every image shown. A two-case suite at 64x36 (one case
# changed after its reference was written, so the page has a failing case with its heat maps)
# is checked, and the page's own script (io/check_report.h) records what loaded in the body's
# attributes, which `chromium --dump-dom` prints once the page has loaded. First the detector
# is shown to catch a missing image and a script error on a broken copy of the page, so this
# test can fail.
# Usage: check_report_browser.sh SSRT
# Without Chromium (`chromium`, in install-deps.sh's ci set) it prints one SKIPPED line and
# exits 77, which ctest reports as skipped; with SSRT_REQUIRE_CHROMIUM=1 (CI) that is a failure.
set -euo pipefail
ssrt=${1:?usage: check_report_browser.sh SSRT}
if ! command -v chromium >/dev/null; then
    echo "check_report_browser: SKIPPED: chromium is not installed (install-deps.sh ci installs it)"
    [ "${SSRT_REQUIRE_CHROMIUM:-0}" = 1 ] && { echo "check_report_browser: FAIL: CI requires it" >&2; exit 1; }
    exit 77
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# load PAGE: prints the page's body tag; fails on any console line from Chromium.
load() {
    timeout 120 chromium --headless --no-sandbox --disable-gpu --no-first-run \
        --user-data-dir="$dir/profile" --enable-logging=stderr --v=0 \
        --dump-dom "file://$1" >"$dir/dom.html" 2>"$dir/chromium.log"
    if grep -q ':CONSOLE' "$dir/chromium.log"; then
        grep ':CONSOLE' "$dir/chromium.log" >&2
        echo "check_report_browser: console messages on $1" >&2
        return 1
    fi
    grep -o '<body[^>]*>' "$dir/dom.html"
}
# good PAGE: the page loaded every one of its images and had no script error.
good() {
    local body images
    body=$(load "$1") || return 1
    images=$(grep -o '<img ' "$1" | wc -l)
    echo "check_report_browser: $body"
    [[ $body == *'data-loaded="yes"'* && $body == *'data-images-failed=""'* &&
       $body == *'data-errors=""'* && $body == *"data-images=\"$images\""* && $images -gt 0 ]]
}

cat >"$dir/suite.json" <<'JSON'
{"cases": [
  {"name": "spheres", "reference": "golden/spheres.exr",
   "render": ["--scene", "spheres", "--width", "64", "--height", "36"]},
  {"name": "cornell", "reference": "golden/cornell.png",
   "render": ["--scene", "cornell", "--width", "64", "--height", "36"]}
]}
JSON
"$ssrt" check "$dir/suite.json" --out "$dir/out" --update >/dev/null
sed -i 's/"--scene", "cornell"/"--scene", "cornell", "--exposure", "1.5"/' "$dir/suite.json"
status=0
"$ssrt" check "$dir/suite.json" --out "$dir/out" >"$dir/check.log" || status=$?
[ $status -eq 1 ] || { cat "$dir/check.log"; echo "check_report_browser: expected exit 1, got $status" >&2; exit 1; }

# The detector first: a copy with a missing image and a script error must not pass.
sed 's|</body>|<img src="no-such.png"><script>notDefined();</script></body>|' \
    "$dir/out/report.html" >"$dir/out/broken.html"
if good "$dir/out/broken.html" 2>/dev/null; then
    echo "check_report_browser: FAIL: a broken page passed the check" >&2
    exit 1
fi
good "$dir/out/report.html" || { echo "check_report_browser: FAIL: the report did not load cleanly" >&2; exit 1; }
echo "check_report_browser: the report loaded in $(chromium --version 2>/dev/null | head -1) with every image"
