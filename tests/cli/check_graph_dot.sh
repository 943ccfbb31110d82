#!/usr/bin/env bash
# `ssrt graph --dot` drawn by Graphviz's own dot (install-deps.sh installs it) for every preset,
# with and without SSR, as a single image and as a sequence's frame: dot must accept each and
# draw an SVG with a node per pass and resource; the graph without SSR has no SSR pass or
# resource.
#   check_graph_dot.sh SSRT
set -euo pipefail
ssrt="$1"
command -v dot >/dev/null || { echo "check_graph_dot: Graphviz's dot is not installed (scripts/install-deps.sh)"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0
for quality in low medium high ultra; do
    for extra in "" "--no-ssr" "--frames 8" "--no-ssgi --frames 8 -o x.exr"; do
        # shellcheck disable=SC2086
        "$ssrt" graph --quality "$quality" $extra --dot >"$tmp/g.dot"
        dot -Tsvg "$tmp/g.dot" -o "$tmp/g.svg"
        grep -q '<svg' "$tmp/g.svg"
        nodes=$(grep -c 'shape=' "$tmp/g.dot")  # a box per pass, an ellipse per resource
        drawn=$(grep -c 'class="node"' "$tmp/g.svg")
        [ "$drawn" -eq "$nodes" ] || { echo "check_graph_dot: $quality $extra: $drawn nodes drawn for $nodes declared"; exit 1; }
        if [ "$extra" = "--no-ssr" ] && grep -qi 'label="ssr' "$tmp/g.dot"; then
            echo "check_graph_dot: --no-ssr still has an SSR node:"; grep -i 'label="ssr' "$tmp/g.dot"; exit 1
        fi
        n=$((n + 1))
    done
done
echo "check_graph_dot: dot drew $n graphs"
