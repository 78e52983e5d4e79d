#!/usr/bin/env bash
# Counts the instructions of one frame of the M1 scene of shared/bench/WORKLOADS.md (Suzanne, 968
# triangles, 320x240 Rgb565) for each combination of pipeline stages with callgrind, and prints a
# markdown table (instructions per frame, per mesh triangle, per drawn triangle, ratio to `m1`) and
# the RenderStats of each frame.
#
# Usage (from anywhere; paths are relative to the repo root):
#   scripts/callgrind3d.sh                  # every combination
#   scripts/callgrind3d.sh m1 m1_nodepth    # only these
#   ANNOTATE=1 scripts/callgrind3d.sh       # also write callgrind_annotate --auto=yes --inclusive=no
#                                           # reports next to the outputs
#
# Honours CARGO_TARGET_DIR. Outputs go to $CARGO_TARGET_DIR/callgrind (default target/callgrind).
# Build: --release, default x86-64 target, no target-cpu=native (RUSTFLAGS is cleared for the build).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
OUT="$TARGET_DIR/callgrind"
TRIANGLES=968

ALL=(m1 m1_nodepth m1_nocull m1_unlit m1_flat m1_phong m1_unlit_nodepth_nocull m1_wireframe
    m1_cached m1_depth_always m1_cull_keepall m1_band8 m1_band16 m1_band32 m1_band240
    m1_band16_cached)
if [ "$#" -gt 0 ]; then
    COMBOS=("$@")
else
    COMBOS=("${ALL[@]}")
fi

# shellcheck source=lib/callgrind-common.sh
source "$ROOT/scripts/lib/callgrind-common.sh"
ensure_valgrind
build_example count3d
mkdir -p "$OUT"

# count COMBINATION: prints the instructions of the counted frame (the call of frame_COMBINATION).
# Only one frame_* function runs per process, so the pattern's trailing wildcard (the symbol hash)
# cannot pick up another combination's function.
count() {
    local combo="$1"
    local file="$OUT/3d-$combo.out"
    rm -f "$file"
    valgrind --tool=callgrind --toggle-collect="*::frame_${combo}*" --callgrind-out-file="$file" \
        "$BIN" "$combo" >"$OUT/3d-$combo.stdout" 2>"$OUT/3d-$combo.log" || {
        echo "valgrind failed for $combo, see $OUT/3d-$combo.log" >&2
        return 1
    }
    local total
    total="$(awk '/^totals:/ {print $2; found=1} END {if (!found) exit 1}' "$file" ||
        awk '/^summary:/ {print $2}' "$file")"
    if [ -z "$total" ] || [ "$total" -eq 0 ]; then
        echo "no instructions collected for $combo: did frame_$combo get inlined or merged?" >&2
        return 1
    fi
    if [ "${ANNOTATE:-0}" = "1" ]; then
        callgrind_annotate --auto=yes --inclusive=no "$file" >"$OUT/3d-$combo.annotate.txt" 2>/dev/null || true
    fi
    echo "$total"
}

# stat COMBINATION KEY: a field of the RenderStats line the example printed.
stat() { sed -n "s/.* $2=\([0-9]*\).*/\1/p" "$OUT/3d-$1.stdout"; }

declare -A INSTR
for combo in "${COMBOS[@]}"; do
    echo "counting $combo..." >&2
    INSTR[$combo]="$(count "$combo")"
done
if [ -z "${INSTR[m1]:-}" ]; then
    echo "counting m1 (the reference of the ratio)..." >&2
    INSTR[m1]="$(count m1)"
fi

div() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN {printf f, (b == 0 ? 0 : a / b)}'; }
thousands() { printf "%s" "$1" | sed ':a;s/\B[0-9]\{3\}\>/,&/;ta'; }

echo
echo "M1 (Suzanne, $TRIANGLES triangles, 320x240 Rgb565), one frame, callgrind, $(date +%Y-%m-%d):"
echo
echo "| combination | instructions / frame | per triangle (/ $TRIANGLES) | drawn | culled | per drawn triangle | vs m1 |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for combo in "${COMBOS[@]}"; do
    n="${INSTR[$combo]}"
    drawn="$(stat "$combo" drawn)"
    culled="$(stat "$combo" culled)"
    echo "| \`$combo\` | $(thousands "$n") | $(thousands "$(div "$n" "$TRIANGLES" "%.0f")") | $drawn | $culled |" \
        "$(thousands "$(div "$n" "$drawn" "%.0f")") | $(div "$n" "${INSTR[m1]}" "%.3f") |"
done
echo
echo "RenderStats of each counted frame:"
echo
echo '```'
for combo in "${COMBOS[@]}"; do
    cat "$OUT/3d-$combo.stdout"
done
echo '```'

# The controls: an effect present but doing nothing must not be cheaper than the pipeline built
# without it (the zero-sized "off" stage must cost less or equal).
control() {
    local off="$1" present="$2" what="$3"
    if [ -n "${INSTR[$off]:-}" ] && [ -n "${INSTR[$present]:-}" ]; then
        local verdict="holds"
        if [ "${INSTR[$off]}" -gt "${INSTR[$present]}" ]; then verdict="FAILS"; fi
        echo "- $what: \`$off\` $(thousands "${INSTR[$off]}") <= \`$present\` $(thousands "${INSTR[$present]}")" \
            "(saves $(thousands $((INSTR[$present] - INSTR[$off]))), $(div "$((100 * (INSTR[$present] - INSTR[$off])))" "${INSTR[$present]}" "%.1f") %): $verdict"
    fi
}
echo
echo "Controls (the zero-sized off stage must cost no more than the stage present but doing nothing):"
echo
control m1_nodepth m1_depth_always "depth (NoDepth vs DepthBuffer with Compare::Always)"
control m1_nocull m1_cull_keepall "culling (NoCull vs a runtime keep-everything Cull)"
