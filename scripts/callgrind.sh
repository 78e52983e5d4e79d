#!/usr/bin/env bash
# Counts instructions per primitive for the 2D benchmark scenes of shared/bench/WORKLOADS.md with
# callgrind, for our renderer and embedded-graphics 0.8 in the same run, and prints a markdown table.
#
# Usage (from anywhere; paths are relative to the repo root):
#   scripts/callgrind.sh            # all scenes
#   ANNOTATE=1 scripts/callgrind.sh # also write callgrind_annotate --auto=yes reports next to the outputs
#
# Honours CARGO_TARGET_DIR. Outputs go to $CARGO_TARGET_DIR/callgrind (default target/callgrind).
# Build: --release, default x86-64 target, no target-cpu=native (RUSTFLAGS is cleared for the build).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
OUT="$TARGET_DIR/callgrind"

# shellcheck source=lib/callgrind-common.sh
source "$ROOT/scripts/lib/callgrind-common.sh"
ensure_valgrind
build_example count2d
mkdir -p "$OUT"

# count SCENE RENDERER FRAME_FN: prints the instructions of one counted frame.
count() {
    callgrind_count "$OUT/$1-$2" "*${3}*" "$BIN" "$1" "$2"
}

# Primitives per frame, from the generator (the example prints them too).
declare -A PRIMS=([L1]=10000 [T1]=10000 [T2]=100 [G1]=10000)
declare -A TARGET=([L1]="<= 1,200" [T1]="<= 450" [T2]="-" [G1]="<= 1,000")
declare -A OURS EG

for scene in L1 T1 T2; do
    case "$scene" in
        L1) kind=lines ;;
        *) kind=triangles ;;
    esac
    echo "counting $scene..." >&2
    OURS[$scene]="$(count "$scene" ours "frame_ours_$kind")"
    EG[$scene]="$(count "$scene" eg "frame_eg_$kind")"
done
echo "counting G1..." >&2
OURS[G1]="$(count G1 ours frame_ours_gouraud)"
echo "counting LIMIT..." >&2
LIMIT="$(count LIMIT ours frame_limit)"

# Pixels written by one T2 frame: drawn once, natively, into a target that counts every pixel write
# it receives (fill_span / fill_solid lengths, overdraw included); nothing is stored.
T2_PX_OURS="$("$BIN" T2 ours --pixels)"
T2_PX_EG="$("$BIN" T2 eg --pixels)"
PIXELS=76800

div() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN {printf f, a / b}'; }
# share PX INSTR: (PX / INSTR) as a percentage of LIMIT's pixels per instruction.
share() { awk -v p="$1" -v i="$2" -v lp="$PIXELS" -v li="$LIMIT" 'BEGIN {printf "%.1f%%", 100 * (p / i) / (lp / li)}'; }

echo
echo "Instructions per primitive (callgrind, one frame, 320x240 Rgb565, $(date +%Y-%m-%d)):"
echo
echo "| scene | primitives | ours instr/prim | embedded-graphics instr/prim | ours / eg | target (ours) |"
echo "|---|---:|---:|---:|---:|---|"
for scene in L1 T1 T2 G1; do
    n="${PRIMS[$scene]}"
    ours="$(div "${OURS[$scene]}" "$n" "%.0f")"
    if [ -n "${EG[$scene]:-}" ]; then
        eg="$(div "${EG[$scene]}" "$n" "%.0f")"
        ratio="$(div "${OURS[$scene]}" "${EG[$scene]}" "%.2f")"
    else
        eg="n/a (no Gouraud)"
        ratio="-"
    fi
    echo "| $scene | $n | $ours | $eg | $ratio | ${TARGET[$scene]} |"
done
echo "| LIMIT | 1 frame (76,800 px) | $LIMIT | | | |"
echo
limit_ppi="$(div "$PIXELS" "$LIMIT" "%.4f")"
ours_ppi="$(div "$T2_PX_OURS" "${OURS[T2]}" "%.4f")"
eg_ppi="$(div "$T2_PX_EG" "${EG[T2]}" "%.4f")"
echo "T2 fill rate as a share of LIMIT (pixels written per instruction; T2 pixels counted by a"
echo "counting target, overdraw included):"
echo
echo "| renderer | T2 pixels/frame | T2 instr/frame | px/instr | LIMIT px/instr | share of LIMIT | target |"
echo "|---|---:|---:|---:|---:|---:|---|"
echo "| ours | $T2_PX_OURS | ${OURS[T2]} | $ours_ppi | $limit_ppi | $(share "$T2_PX_OURS" "${OURS[T2]}") | >= 60% |"
echo "| embedded-graphics | $T2_PX_EG | ${EG[T2]} | $eg_ppi | $limit_ppi | $(share "$T2_PX_EG" "${EG[T2]}") | |"
