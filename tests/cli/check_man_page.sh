#!/usr/bin/env bash
# The man page the build wrote (`ssrt man`, installed to share/man/man1/ssrt.1), formatted by
# man-db's man with every groff warning on (--warnings=w: groff's "all" leaves out undefined
# macros): it must format without a warning, have the sections a man page has, and give every
# command `ssrt --help` lists with its usage and every flag of that command's --help.
#   check_man_page.sh PAGE SSRT
set -euo pipefail
page="$1" ssrt="$2"
command -v man >/dev/null || { echo "check_man_page: man is not installed (scripts/install-deps.sh installs man-db)"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Plain ASCII at a fixed width: no hyphenation hyphens or bold in the text searched below.
MANWIDTH=100 MAN_KEEP_FORMATTING= LC_ALL=C.UTF-8 man --warnings=w -E ascii -l "$page" \
    >"$tmp/page.txt" 2>"$tmp/warnings.txt"
if [ -s "$tmp/warnings.txt" ]; then
    echo "FAIL: man warns about $page:" >&2
    cat "$tmp/warnings.txt" >&2
    exit 1
fi
col -b <"$tmp/page.txt" >"$tmp/text.txt"
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }
for section in NAME SYNOPSIS DESCRIPTION COMMANDS "EXIT STATUS" "SEE ALSO"; do
    grep -qx "$section" "$tmp/text.txt" || fail "no section $section"
done
mapfile -t commands < <("$ssrt" --help | sed -n '/^Subcommands:/,/^$/p' | awk 'NR > 1 && /^  [a-z]/ { print $1 }')
[ ${#commands[@]} -gt 0 ] || { echo "FAIL: no commands in 'ssrt --help'" >&2; exit 1; }
for c in "${commands[@]}"; do
    grep -q "^ *ssrt $c \[OPTIONS\]" "$tmp/text.txt" || fail "no usage line for 'ssrt $c'"
    # The command's part of the page: from its heading (indented 3) to the next one's.
    awk -v c="$c" '$0 == "   " c { on = 1; next } on && /^(   )?[A-Za-z]/ { exit } on' \
        "$tmp/text.txt" >"$tmp/cmd.txt"
    [ -s "$tmp/cmd.txt" ] || { fail "no section for 'ssrt $c'"; continue; }
    # The flags of the help's option lines ("  -s,--scene NAME=cornell  ...").
    for flag in $("$ssrt" "$c" --help | grep -oE -- '^  +-[^ ]*' | tr ',' '\n' | grep -oE -- '--[a-z0-9-]+' | sort -u); do
        grep -qE -- "(^|[ ,])$flag([ ,]|$)" "$tmp/cmd.txt" || fail "'ssrt $c' has no $flag"
    done
done
grep -qF "$("$ssrt" --help | grep '^Exit status: ' | sed 's/^Exit status: //' | cut -c1-40)" \
    <(tr '\n' ' ' <"$tmp/text.txt" | tr -s ' ') || fail "EXIT STATUS is not the help's exit status"
[ "$failures" -eq 0 ] || exit 1
echo "man page: formats without a warning; ${#commands[@]} commands, each with its flags"
