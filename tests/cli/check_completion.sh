#!/usr/bin/env bash
# The bash completion script the build wrote (`ssrt completion bash`, installed to
# share/bash-completion/completions/ssrt), sourced into bash and asked as bash asks it
# (COMP_WORDS, COMP_CWORD, then the function `complete` names): it completes the commands, a
# command's flags, the built-in scenes after -s/--scene (also as --scene=), file names after an
# option whose value is a file, and the shells after `ssrt completion`.
#   check_completion.sh COMPLETION_SCRIPT SSRT
set -euo pipefail
script=$(realpath "$1") ssrt=$(realpath "$2")
# In an empty folder, so that no file name can join a completion.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
# shellcheck source=/dev/null
source "$script"
function=$(complete -p ssrt | sed -nE 's/.*-F ([^ ]+) .*/\1/p')
[ -n "$function" ] || { echo "FAIL: the script registers no completion function for ssrt" >&2; exit 1; }
failures=0
# expect "WANTED COMPLETIONS" WORD...: the words typed so far, the last one being completed.
expect() {
    local wanted="$1"
    shift
    COMP_WORDS=("$@")
    COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
    COMP_LINE="$*"
    COMP_POINT=${#COMP_LINE}
    COMPREPLY=()
    "$function" ssrt "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD - 1]}" 2>/dev/null
    local got
    got=$(printf '%s\n' "${COMPREPLY[@]}" | sort | xargs)
    if [ "$got" != "$wanted" ]; then
        echo "FAIL: '$*' completes to '$got', expected '$wanted'" >&2
        failures=$((failures + 1))
    fi
}
# Every command `ssrt --help` lists, and nothing else, after `ssrt `.
commands=$("$ssrt" --help | sed -n '/^Subcommands:/,/^$/p' | awk 'NR > 1 && /^  [a-z]/ { print $1 }' | sort | xargs)
[ -n "$commands" ] || { echo "FAIL: no commands in 'ssrt --help'" >&2; exit 1; }
expect "$commands" ssrt ""
expect "reference render" ssrt re
expect "--width" ssrt render --wi
expect "--heatmap --heatmap-layer --heatmap-scale" ssrt diff --heat
expect "cornell corridor" ssrt render -s cor
expect "cornell corridor" ssrt compare --scene cor
expect "cornell corridor" ssrt render --scene = cor
expect "spheres" ssrt graph --width 64 -s sph
expect "" ssrt render --width ""          # a number: nothing to offer
expect "bash" ssrt completion ""
# Every flag of `ssrt render --help` is offered after `ssrt render -`.
flags=$("$ssrt" render --help | grep -oE -- '^  +-[^ ]*' | tr ',' '\n' | grep -oE -- '-[a-z0-9-]+' | sort -u | xargs)
expect "$flags" ssrt render -
# A file after -o, a glTF file or a folder (not another file) after --scene.
touch out.exr scene.gltf notes.txt
mkdir sub
expect "out.exr" ssrt render -o ou
expect "scene.gltf spheres sub" ssrt render --scene s
[ "$failures" -eq 0 ] || exit 1
echo "completion: commands, flags, scenes, files and shells complete"
