#!/usr/bin/env bash
# The README's two commands in a fresh Debian 12 root, as a newcomer types them: a minimal root
# made by Debian's debootstrap (--variant=minbase: apt, dpkg, bash, coreutils, no compiler), a
# clean checkout of the commit copied into it (git archive, no build/ and nothing untracked),
# then, inside it as root:
#   1. ./scripts/render-default.sh   must write cornell.png, byte-identical to the PNG the host's
#                                    build/ssrt renders (same compiler and packages: the
#                                    determinism contract says so);
#   2. ./scripts/test.sh             must pass (SSRT_FRESH_TESTS=none skips it).
# Each command's time is printed, split into packages, build and the rest (render or tests),
# from the lines install-deps.sh and build.sh print; README.md quotes them.
#
#   scripts/test-fresh.sh                   # both commands
#   SSRT_FRESH_TESTS=none scripts/test-fresh.sh   # command 1 only
#   scripts/test-fresh.sh --prepare         # only what waits on the network: the cached root
#                                           # (debootstrap) and the packages the commands will
#                                           # install, downloaded into apt-archives/ (below);
#                                           # .ci/run starts it early, beside the stages that
#                                           # compute, and the fresh stage then finds both
#
# Needs root (debootstrap, chroot, mounts in a private mount namespace that ends with the run).
# Kept outside the checkout, in SSRT_FRESH_CACHE (default /var/cache/ssrt-fresh):
#   root-KEY.tar   the debootstrapped root, made again when this script changes (KEY is its
#                  hash) or when it is older than a week (Debian's updates move on);
#   apt-archives/  the .deb files the roots downloaded (what a newcomer's apt fetches; kept so
#                  a second run does not fetch them again; the packages are still installed);
#   run/           the root of the latest run (removed at the start of the next), and its logs;
# The root is given the host's compiler cache (SSRT_FRESH_CCACHE=1, the default): ccache is
# installed in the root before the commands and the host's cache folder (`ccache -k cache_dir`)
# mounted as the root's, so the commands compile through it as on any machine that has ccache
# (scripts/lib/compiler-cache.sh finds it; the commands are unchanged). The root's compiler is
# the host's (the same Debian packages) and the cache is keyed on paths relative to the
# checkout, so what CI's test stage compiled on the host is a hit in the root: a cold machine
# builds the project once, not three times. The hits and misses are printed.
# SSRT_FRESH_CCACHE=0: no ccache in the root, every build a newcomer's cold build (the times
# docs/ci.md quotes for a newcomer).
# Where debootstrap cannot reach the package archive it prints one line
# "test-fresh: SKIPPED: ..." and exits 0; any other failure fails.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
self="$repo/scripts/test-fresh.sh"
t_start=$SECONDS
say() { echo "test-fresh: $*" >&2; }

readonly kSuite=bookworm
readonly kMaxAgeDays=7
cache="${SSRT_FRESH_CACHE:-/var/cache/ssrt-fresh}"
tests="${SSRT_FRESH_TESTS:-all}"
use_ccache="${SSRT_FRESH_CCACHE:-1}"
prepare=0
case "${1:-}" in
    "") ;;
    --prepare) prepare=1 ;;
    *) say "usage: $0 [--prepare]"; exit 2 ;;
esac
case "$tests" in all | none) ;; *) say "SSRT_FRESH_TESTS must be all or none"; exit 2 ;; esac
[ "$(id -u)" -eq 0 ] || { say "needs root (debootstrap, chroot and mounts)"; exit 2; }

passed=0
failed=0
pass() { say "ok: $*"; passed=$((passed + 1)); }
fail() { say "FAIL: $*"; failed=$((failed + 1)); }
# The root's compiler cache (set below) and what its builds found there, said at the end.
ccache_dir=""
ccache_count() { # the cache's hits and misses so far: "HITS MISSES"
    ccache --print-stats | awk '$1 ~ /_cache_hit$/ { h += $2 } $1 == "cache_miss" { m = $2 }
        END { print h + 0, m + 0 }'
}
ccache_summary() { # how much the root's builds found in the host's cache
    [ -n "$ccache_dir" ] || return 0
    local hits misses
    read -r hits misses <<<"$(ccache_count)"
    say "the root's builds: $((hits - hits0)) compiler cache hits, $((misses - misses0)) misses"
}
finish() {
    ccache_summary
    say "took $((SECONDS - t_start)) s"
    say "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}

bash scripts/install-deps.sh ci

# The archive the host's apt uses (its sources, not a name written here): the first URI of a
# "deb" source for the suite, from deb822 .sources files or one-line sources.list entries.
mirror="$(
    { cat /etc/apt/sources.list.d/*.sources 2>/dev/null; echo; } |
        awk -v suite="$kSuite" 'BEGIN { RS = ""; FS = "\n" }
            $0 ~ "(^|\n)Types:[^\n]*deb([ \t\n]|$)" &&
            $0 ~ ("(^|\n)Suites:[^\n]*[ \t]" suite "([ \t\n]|$)") {
                for (i = 1; i <= NF; i++) if ($i ~ /^URIs:/) { split($i, u, /[ \t]+/); print u[2]; exit }
            }'
)"
if [ -z "$mirror" ]; then
    mirror="$(awk -v suite="$kSuite" '$1 == "deb" && $3 == suite { print $2; exit }' \
        /etc/apt/sources.list 2>/dev/null || true)"
fi
[ -n "$mirror" ] || { fail "no Debian archive for $kSuite in the host's apt sources"; finish; }

# The newcomer's commands install packages, and debootstrap fetches them: without the archive
# there is nothing to try (the one case this test skips).
if ! wget -q -T 20 -t 2 -O /dev/null "$mirror/dists/$kSuite/Release"; then
    say "SKIPPED: debootstrap cannot reach the package archive ($mirror/dists/$kSuite/Release)"
    exit 0
fi

# The cached minimal root: made again when this script changes or after a week.
key="$(sha256sum "$self" | cut -c1-16)"
tarball="$cache/root-$key.tar"
mkdir -p "$cache/apt-archives/partial"
if [ -f "$tarball" ] && [ -z "$(find "$tarball" -mtime +"$((kMaxAgeDays - 1))")" ]; then
    say "cached root $tarball ($(( ($(date +%s) - $(stat -c %Y "$tarball")) / 86400 )) days old)"
else
    rm -f "$cache"/root-*.tar
    t0=$SECONDS
    staging="$cache/staging"
    rm -rf "$staging"
    if ! debootstrap --variant=minbase "$kSuite" "$staging" "$mirror" >"$cache/debootstrap.log" 2>&1; then
        tail -n 20 "$cache/debootstrap.log" >&2
        fail "debootstrap --variant=minbase $kSuite failed (log above)"
        finish
    fi
    rm -rf "$staging"/var/cache/apt/archives/*.deb
    tar -C "$staging" -cf "$tarball.tmp" . && mv "$tarball.tmp" "$tarball"
    rm -rf "$staging"
    say "debootstrapped a minimal $kSuite root in $((SECONDS - t0)) s ($tarball)"
fi

# A new root for this run, from the cached one; the host's apt sources (the same suites,
# updates and security as a newcomer's fresh install has, so the same package versions as the
# host's) and resolver.
run="$cache/run"
rm -rf "$run"
mkdir -p "$run/root" "$run/logs"
root="$run/root"
tar -C "$root" -xf "$tarball"
rm -f "$root/etc/apt/sources.list"
cp -L /etc/apt/sources.list "$root/etc/apt/" 2>/dev/null || true
cp -L /etc/apt/sources.list.d/*.sources "$root/etc/apt/sources.list.d/" 2>/dev/null || true
cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true

# A clean checkout of the commit, where a newcomer clones it.
rev="${SSRT_FRESH_REV:-HEAD}"
mkdir -p "$root/root/ssrt"
git -C "$repo" archive --format=tar "$rev" | tar -C "$root/root/ssrt" -xf -
say "root ready: $(git -C "$repo" rev-parse --short "$rev") in $root/root/ssrt"

# Runs a command in the root (bash -c), its output in logs/NAME.log; returns its status. The
# environment is a newcomer's login: HOME, TERM, PATH and the host's LANG (C.UTF-8 if unset),
# which ccache hashes (compiler messages follow it): without it no unit would be found in the
# host's cache.
in_root() { # name, command
    local name="$1" cmd="$2"
    unshare --mount --propagation private -- bash -c '
        set -e
        root="$1"
        mount -t proc proc "$root/proc"
        mount --rbind /dev "$root/dev"
        mount --bind "$2" "$root/var/cache/apt/archives"
        if [ -n "$4" ]; then
            mkdir -p "$root/root/.cache/ccache"
            mount --bind "$4" "$root/root/.cache/ccache"
        fi
        exec chroot "$root" /usr/bin/env -i HOME=/root TERM=dumb LANG="$5" \
            PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
            /bin/bash -c "cd /root/ssrt && $3"
    ' bash "$root" "$cache/apt-archives" "$cmd" "$ccache_dir" "${LANG:-C.UTF-8}" \
        >"$run/logs/$name.log" 2>&1
}

# --prepare: the packages the two commands install, downloaded (not installed) into the kept
# apt-archives/, from which the commands' apt then installs without fetching them.
if [ "$prepare" = 1 ]; then
    t0=$SECONDS
    if in_root download "bash scripts/install-deps.sh download"; then
        pass "prepared: the root and its packages downloaded in $((SECONDS - t0)) s ($(du -sh "$cache/apt-archives" | cut -f1) in apt-archives/)"
    else
        tail -n 20 "$run/logs/download.log" | sed 's/^/  | /' >&2
        fail "downloading the packages in the root failed (log above)"
    fi
    finish
fi

# The root's compiler cache: the host's (see the header).
rm -rf "$cache/ccache" # (the root's own cache, before it was given the host's)
if [ "$use_ccache" = 1 ]; then
    ccache_dir="$(ccache -k cache_dir)"
    mkdir -p "$ccache_dir"
    read -r hits0 misses0 <<<"$(ccache_count)"
    if ! in_root ccache "apt-get update -q && apt-get install -y -q --no-install-recommends ccache"; then
        tail -n 20 "$run/logs/ccache.log" | sed 's/^/  | /' >&2
        fail "installing ccache in the root failed (log above)"
        finish
    fi
    say "ccache in the root, the host's cache $ccache_dir ($(du -sh "$ccache_dir" | cut -f1))"
fi
# "packages P s, build B s, OTHER R s" from a log and the command's time.
split_time() { # log, total seconds, name of the rest
    local p b
    p=$(sed -n 's/^install-deps: installed .* in \([0-9]*\) s$/\1/p' "$1" | awk '{s += $1} END {print s + 0}')
    b=$(sed -n 's/^build: .* in \([0-9]*\) s$/\1/p' "$1" | awk '{s += $1} END {print s + 0}')
    echo "packages $p s, build $b s, $3 $(($2 - p - b)) s"
}

# README command 1.
t0=$SECONDS
if in_root render "./scripts/render-default.sh"; then
    t1=$((SECONDS - t0))
    tail -n 3 "$run/logs/render.log" | sed 's/^/  | /' >&2
    if [ -s "$root/root/ssrt/cornell.png" ]; then
        pass "command 1, ./scripts/render-default.sh, wrote cornell.png in $t1 s ($(split_time "$run/logs/render.log" "$t1" render))"
    else
        fail "command 1, ./scripts/render-default.sh, exited 0 without writing cornell.png"
    fi
else
    tail -n 20 "$run/logs/render.log" | sed 's/^/  | /' >&2
    fail "command 1, ./scripts/render-default.sh, failed after $((SECONDS - t0)) s (log above: $run/logs/render.log)"
fi

# The same PNG from the host's build.
if [ -s "$root/root/ssrt/cornell.png" ]; then
    [ -x build/ssrt ] || bash scripts/build.sh --render >/dev/null
    ./build/ssrt render --quiet -o "$run/host.png"
    if cmp -s "$run/host.png" "$root/root/ssrt/cornell.png"; then
        pass "the fresh root's cornell.png is the host's, byte for byte ($(stat -c %s "$run/host.png") bytes)"
    else
        fail "the fresh root's cornell.png differs from the host's ($run/host.png, $root/root/ssrt/cornell.png)"
    fi
fi

# README command 2.
if [ "$tests" = all ]; then
    t0=$SECONDS
    if in_root tests "./scripts/test.sh"; then
        t2=$((SECONDS - t0))
        summary="$(grep -E '^[0-9]+% tests passed' "$run/logs/tests.log" | tail -n 1)"
        pass "command 2, ./scripts/test.sh, passed in $t2 s ($(split_time "$run/logs/tests.log" "$t2" tests); $summary)"
    else
        tail -n 30 "$run/logs/tests.log" | sed 's/^/  | /' >&2
        # The failed tests' own lines (ctest prints their output above its summary, which a
        # CI log that keeps only this script's output would otherwise lose).
        grep -E 'FAIL|\*\*\*Failed|ERROR|error:' "$run/logs/tests.log" | head -n 40 |
            sed 's/^/  ! /' >&2 || true
        fail "command 2, ./scripts/test.sh, failed after $((SECONDS - t0)) s (log above: $run/logs/tests.log)"
    fi
fi
finish
