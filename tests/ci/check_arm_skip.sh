#!/usr/bin/env bash
# scripts/test-arm.sh skips with one line, exit 0, only where the arm64 packages cannot be
# installed (issue 31): here apt cannot find them (fake dpkg-query, dpkg, apt-get and sudo on
# PATH say the arm64 copies are missing and the archive has none), so the script must print
# `test-arm: SKIPPED: the arm64 packages cannot be installed: <apt's last line>` and nothing
# else, build nothing and exit 0. The host's packages are the real dpkg-query's answer.
# Usage: check_arm_skip.sh SOURCE_DIR
set -euo pipefail
src="$1"
fake=$(mktemp -d)
trap 'rm -rf "$fake"' EXIT
real_query=$(command -v dpkg-query)
real_dpkg=$(command -v dpkg)
cat >"$fake/dpkg-query" <<EOS
#!/bin/sh
for a in "\$@"; do case "\$a" in *:arm64) exit 1 ;; esac; done
exec "$real_query" "\$@"
EOS
cat >"$fake/dpkg" <<EOS
#!/bin/sh
case "\$1" in --print-foreign-architectures|--add-architecture) exit 0 ;; esac
exec "$real_dpkg" "\$@"
EOS
cat >"$fake/apt-get" <<'EOS'
#!/bin/sh
echo "E: Unable to locate package libxsimd-dev:arm64" >&2
exit 100
EOS
printf '#!/bin/sh\nexec "$@"\n' >"$fake/sudo"
chmod +x "$fake"/*

before=$(ls -d "$src"/build-arm 2>/dev/null || true)
set +e
out=$(PATH="$fake:$PATH" bash "$src/scripts/test-arm.sh" 2>&1)
code=$?
set -e
expected="test-arm: SKIPPED: the arm64 packages cannot be installed: E: Unable to locate package libxsimd-dev:arm64"
if [ "$code" -ne 0 ] || [ "$out" != "$expected" ]; then
    echo "check_arm_skip: expected exit 0 and the one line" >&2
    echo "  $expected" >&2
    echo "got exit $code and:" >&2
    echo "$out" | sed 's/^/  /' >&2
    exit 1
fi
after=$(ls -d "$src"/build-arm 2>/dev/null || true)
[ "$before" = "$after" ] || { echo "check_arm_skip: the skip made build-arm/" >&2; exit 1; }
echo "check_arm_skip: ok ($out)"
