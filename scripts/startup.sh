#!/usr/bin/env bash
# Start-up time of each demo scene, cold and warm: `bash scripts/startup.sh [runs]` (default 3).
# Cold: an empty XDG_CACHE_HOME, so HFX's program binaries, PoCL's kernel
# cache and Mesa's shader cache all start empty. Warm: the same folder again. "HFX cache only":
# warm, with PoCL's own kernel cache turned off (POCL_KERNEL_CACHE=0), as on a driver that keeps
# none. Each run renders one 1280x720 frame headless and writes it. Prints a Markdown table of
# medians (docs/history/tuning.md).
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-3}"
demo=build/demo/hfx-demo
[ -x "$demo" ] || { echo "build first: bash scripts/build.sh" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# seconds and the kernel line's "N ms" of one run
run_once() {
    local cache="$1"; shift
    local start end
    start=$(date +%s.%N)
    env XDG_CACHE_HOME="$cache" "$@" "$demo" "$scene" --headless --frames 1 --out "$work/frames" \
        --no-progress > /dev/null 2> "$work/log" || { cat "$work/log" >&2; exit 1; }
    end=$(date +%s.%N)
    local programs
    programs=$(sed -n 's/^hfx: kernels: [0-9]* programs in \([0-9]*\) ms.*/\1/p' "$work/log")
    awk -v a="$start" -v b="$end" -v p="${programs:-0}" 'BEGIN { printf "%.3f %s\n", b - a, p }'
}

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR + 1) / 2)]}'; }

echo "| scene | cold s | warm s | cold / warm | HFX cache only s | cold / HFX only | programs cold / warm ms |"
echo "|---|---|---|---|---|---|---|"
for scene in water decals planet; do
    : > "$work/cold"; : > "$work/warm"; : > "$work/hfxonly"
    for ((i = 0; i < runs; ++i)); do
        cache="$work/cache$i"
        rm -rf "$cache"; mkdir -p "$cache"
        run_once "$cache" >> "$work/cold"
        run_once "$cache" >> "$work/warm"
        run_once "$cache" POCL_KERNEL_CACHE=0 >> "$work/hfxonly"
    done
    cold=$(cut -d' ' -f1 "$work/cold" | median)
    warm=$(cut -d' ' -f1 "$work/warm" | median)
    only=$(cut -d' ' -f1 "$work/hfxonly" | median)
    pcold=$(cut -d' ' -f2 "$work/cold" | median)
    pwarm=$(cut -d' ' -f2 "$work/warm" | median)
    awk -v s="$scene" -v c="$cold" -v w="$warm" -v o="$only" -v pc="$pcold" -v pw="$pwarm" 'BEGIN {
        printf "| %s | %.2f | %.2f | %.1fx | %.2f | %.1fx | %s / %s |\n", s, c, w, c / w, o, c / o, pc, pw }'
done
