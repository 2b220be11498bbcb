#!/usr/bin/env bash
# Screenshots of a rendered report for a person to look at: the top of the page and every
# section (each <h2 id> and <section id> of index.html), with headless Chromium: the first
# screen at 1280 × 800 px (what a reader sees on opening the page), each section at 1280 × 1000;
# with FIGURES=1 also every figure (<figure id>).
# Usage: [FIGURES=1] scripts/screenshot.sh [REPORT_DIR (reports/paper)] [OUT_DIR (target/screenshots)]
# A section is shown by loading the page in an iframe at index.html#id (headless Chromium does
# not scroll the top-level page to a fragment before the capture).
set -euo pipefail
report="${1:-reports/paper}"
out="${2:-target/screenshots}"
browser="${CHROMIUM:-}"
if [ -z "$browser" ]; then
    for b in chromium chromium-browser google-chrome; do
        if command -v "$b" >/dev/null 2>&1; then browser="$b"; break; fi
    done
fi
if [ -z "$browser" ]; then
    echo "screenshot: no headless Chromium found (set CHROMIUM=/path/to/chromium)" >&2
    exit 1
fi
if [ ! -f "$report/index.html" ]; then
    echo "screenshot: $report/index.html not found; run 'wingcheck report --out $report' first" >&2
    exit 1
fi
mkdir -p "$out"
rm -f "$out"/[0-9][0-9]-*.png
profile="$(mktemp -d)"
trap 'rm -rf "$profile"' EXIT
index="$(cd "$report" && pwd)/index.html"
shot() { # name url [width,height]
    "$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars --virtual-time-budget=10000 \
        --no-first-run --disable-background-networking --disable-component-update --disable-sync \
        --user-data-dir="$profile" --window-size="${3:-1280,1000}" --screenshot="$out/$1.png" "$2" >/dev/null 2>&1
    echo "$out/$1.png"
}
shot 00-top "file://$index" 1280,800
n=1
tags='h2|section'
if [ "${FIGURES:-0}" = 1 ]; then tags='h2|section|figure'; fi
for id in $(grep -oE "<($tags)[^>]* id=\"[^\"]+\"" "$index" | sed -E 's/.* id="([^"]+)"/\1/'); do
    wrapper="$out/.frame-$id.html"
    printf '<!DOCTYPE html><html><head><style>body{margin:0}iframe{border:0;width:1280px;height:1000px}</style></head><body><iframe src="file://%s#%s"></iframe></body></html>\n' "$index" "$id" >"$wrapper"
    shot "$(printf '%02d' "$n")-$id" "file://$(cd "$out" && pwd)/.frame-$id.html"
    rm -f "$wrapper"
    n=$((n + 1))
done
