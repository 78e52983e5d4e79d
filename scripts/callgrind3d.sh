#!/usr/bin/env bash
# Counts the instructions of one frame of the mesh scenes of shared/bench/WORKLOADS.md (M1 Suzanne,
# 968 triangles; M2 Stanford bunny res3, 3,851; M3 full Stanford bunny, 69,451; 320x240 Rgb565) with
# callgrind, for each combination of pipeline stages and for the comparison renderer euc, and prints
# markdown tables (instructions per frame, per mesh triangle, per drawn triangle, ratio to the
# scene's `m1`; ours against euc) and the RenderStats of each frame.
#
# A job is SCENE:COMBINATION (count3d --scene SCENE COMBINATION), or COMBINATION for M1. The
# combination names are count3d's (`m1` is the headline pipeline whatever the scene; `euc` is euc).
#
# Usage (from anywhere; paths are relative to the repo root):
#   scripts/callgrind3d.sh                  # every M1 combination, the shading models on M2 and M3,
#                                           # and euc on all three
#   scripts/callgrind3d.sh m1 m1_nodepth    # only these (M1)
#   scripts/callgrind3d.sh M2:m1 M2:euc     # M2
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

# count3d's combinations: `m1` and the bands draw with a vertex scratch, `*_noscratch` without.
M1_ALL=(m1 m1_noscratch m1_nodepth m1_nocull m1_unlit m1_flat m1_phong m1_unlit_nodepth_nocull
    m1_wireframe m1_depth_always m1_cull_keepall m1_band8 m1_band16 m1_band32 m1_band240
    m1_band16_noscratch euc)
# M2 and M3: the shading models (Gouraud is the headline), the draw without a vertex scratch and euc.
MESH_ALL=(m1 m1_noscratch m1_unlit m1_flat m1_phong m1_wireframe euc)
if [ "$#" -gt 0 ]; then
    JOBS=()
    for job in "$@"; do
        case "$job" in
        *:*) JOBS+=("$job") ;;
        *) JOBS+=("M1:$job") ;;
        esac
    done
else
    JOBS=()
    for c in "${M1_ALL[@]}"; do JOBS+=("M1:$c"); done
    for scene in M2 M3; do
        for c in "${MESH_ALL[@]}"; do JOBS+=("$scene:$c"); done
    done
fi

# shellcheck source=lib/callgrind-common.sh
source "$ROOT/scripts/lib/callgrind-common.sh"
ensure_valgrind
build_example count3d
mkdir -p "$OUT"

# count SCENE COMBINATION: prints the instructions of the counted frame (the call of
# frame_COMBINATION). Only one frame_* function runs per process, so the pattern's trailing wildcard
# (the symbol hash) cannot pick up another combination's function.
count() {
    callgrind_count "$OUT/3d-$1-$2" "*::frame_${2}*" "$BIN" --scene "$1" "$2"
}

# stat SCENE COMBINATION KEY: a field of the stats line the example printed.
stat() { sed -n "s/.* $3=\([0-9]*\).*/\1/p" "$OUT/3d-$1-$2.stdout"; }

declare -A INSTR
for job in "${JOBS[@]}"; do
    echo "counting $job..." >&2
    INSTR[$job]="$(count "${job%%:*}" "${job#*:}")"
done
# The reference of each scene's ratio column.
for job in "${JOBS[@]}"; do
    scene="${job%%:*}"
    if [ -z "${INSTR[$scene:m1]:-}" ]; then
        echo "counting $scene:m1 (the reference of the ratio)..." >&2
        INSTR[$scene:m1]="$(count "$scene" m1)"
    fi
done

div() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN {printf f, (b == 0 ? 0 : a / b)}'; }
thousands() { printf "%s" "$1" | sed ':a;s/\B[0-9]\{3\}\>/,&/;ta'; }

echo
echo "One frame, callgrind, 320x240 Rgb565, $(date +%Y-%m-%d):"
echo
echo "| scene | combination | triangles | instructions / frame | per triangle | drawn | culled | per drawn triangle | vs the scene's m1 |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
for job in "${JOBS[@]}"; do
    scene="${job%%:*}"
    combo="${job#*:}"
    n="${INSTR[$job]}"
    tris="$(stat "$scene" "$combo" triangles)"
    drawn="$(stat "$scene" "$combo" drawn)"
    culled="$(stat "$scene" "$combo" culled)"
    echo "| $scene | \`$combo\` | $(thousands "$tris") | $(thousands "$n") | $(thousands "$(div "$n" "$tris" "%.0f")") |" \
        "$(thousands "$drawn") | $(thousands "$culled") | $(thousands "$(div "$n" "$drawn" "%.0f")") |" \
        "$(div "$n" "${INSTR[$scene:m1]}" "%.3f") |"
done

# Ours against euc, for each scene where euc was counted.
echo
echo "Ours (Gouraud + depth + back faces culled) against euc, instructions per frame:"
echo
echo "| scene | triangles | ours \`m1\` | ours \`m1_noscratch\` | euc | m1 / euc | m1_noscratch / euc |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for scene in M1 M2 M3; do
    euc="${INSTR[$scene:euc]:-}"
    [ -n "$euc" ] || continue
    m1="${INSTR[$scene:m1]}"
    noscratch="${INSTR[$scene:m1_noscratch]:-}"
    tris="$(stat "$scene" euc triangles)"
    noscratch_col="-"
    noscratch_ratio="-"
    if [ -n "$noscratch" ]; then
        noscratch_col="$(thousands "$noscratch")"
        noscratch_ratio="$(div "$noscratch" "$euc" "%.3f")"
    fi
    echo "| $scene | $(thousands "$tris") | $(thousands "$m1") | $noscratch_col | $(thousands "$euc") |" \
        "$(div "$m1" "$euc" "%.3f") | $noscratch_ratio |"
done

echo
echo "Stats of each counted frame:"
echo
echo '```'
for job in "${JOBS[@]}"; do
    cat "$OUT/3d-${job%%:*}-${job#*:}.stdout"
done
echo '```'

# The controls: an effect present but doing nothing must not be cheaper than the pipeline built
# without it (the zero-sized "off" stage must cost less or equal).
control() {
    local off="M1:$1" present="M1:$2" what="$3"
    if [ -n "${INSTR[$off]:-}" ] && [ -n "${INSTR[$present]:-}" ]; then
        local verdict="holds"
        if [ "${INSTR[$off]}" -gt "${INSTR[$present]}" ]; then verdict="FAILS"; fi
        echo "- $what: \`$1\` $(thousands "${INSTR[$off]}") <= \`$2\` $(thousands "${INSTR[$present]}")" \
            "(saves $(thousands $((INSTR[$present] - INSTR[$off]))), $(div "$((100 * (INSTR[$present] - INSTR[$off])))" "${INSTR[$present]}" "%.1f") %): $verdict"
    fi
}
echo
echo "Controls on M1 (the zero-sized off stage must cost no more than the stage present but doing nothing):"
echo
control m1_nodepth m1_depth_always "depth (NoDepth vs DepthBuffer with Compare::Always)"
control m1_nocull m1_cull_keepall "culling (NoCull vs a runtime keep-everything Cull)"
