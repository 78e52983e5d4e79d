#!/usr/bin/env bash
# Runs every count of shared/bench/WORKLOADS.md and prints the figures of record: one line per
# figure on stdout, `scene<TAB>renderer<TAB>metric<TAB>value` (plain integers or decimals), in a
# fixed order. Progress and build output go to stderr. BENCHMARKS.md and README.md take their
# tables from this output, committed as docs/figures.tsv:
#
#   scripts/figures.sh -o docs/figures.tsv && cargo run -p host-tools --example figures_tables -- docs/figures.tsv
#
# Usage (from anywhere; paths are relative to the repo root):
#   scripts/figures.sh                  # every figure
#   scripts/figures.sh --quick          # only the lines WORKLOADS.md's table requires
#   scripts/figures.sh T2 M1            # only these scenes (L1 T1 T2 G1 P1 LIMIT, the mesh scenes, S1, I1)
#   scripts/figures.sh -o FILE          # also write the lines to FILE (or FIGURES_OUT=FILE), which is
#                                       # replaced only once every count has succeeded
#   ANNOTATE=1 scripts/figures.sh ...   # also callgrind_annotate reports next to the outputs
#
# What it runs: count2d and count3d (host-tools examples) under callgrind, one process per frame,
# collecting only inside the frame function (--toggle-collect); count2d --stats and
# count3d compare natively for pixels and the ours-against-euc pictures; tests/tests/stack.rs in
# release for the RAM figures (its MEMORY lines); nostd-check built per configuration for .text.
# Every build is --release for the default x86-64 target with RUSTFLAGS cleared (no
# target-cpu=native), but for `text_bytes_thumbv7em`: the same nostd-check configurations built
# for a Cortex-M4F (thumbv7em-none-eabihf, which rustup adds when missing), the flash they need.
# Honours CARGO_TARGET_DIR; each count's files go to $CARGO_TARGET_DIR/figures.
# Any count that fails, or comes out empty or zero, stops the script with a non-zero status.
set -euo pipefail

# The count3d combination behind each renderer name WORKLOADS.md requires. `ours` is the default
# configuration exactly as the README's 3D example builds it (Pipeline::draw, Gouraud, depth buffer,
# back faces culled, default numerics).
DEFAULT_COMBINATION=m1
PHONG_COMBINATION=m1_phong
# The default configuration in 16-row bands (with its vertex scratch); its RAM and code size are
# those of the stack test's and nostd-check's configuration named below (keep the two in step).
BAND16_COMBINATION=m1_band16
BAND16_MEMORY=gouraud_depth_cull_banded16

# The mesh scenes, one line each: SCENE, the count3d combinations whose lines WORKLOADS.md
# requires (all that --quick runs), `|`, the others. A combination is counted as renderer
# `ours-COMBINATION` unless it is one of the above or is written COMBINATION=RENDERER. A scene
# with euc also gets the ours/euc ratio and count3d's picture comparison.
MESH_SCENES=(
    "M1 $DEFAULT_COMBINATION $PHONG_COMBINATION $BAND16_COMBINATION euc | m1_noscratch m1_nodepth m1_nocull m1_unlit m1_flat m1_unlit_nodepth_nocull m1_wireframe m1_depth_always m1_cull_keepall m1_band8 m1_band16_noscratch m1_band32 m1_band240"
    "M2 $DEFAULT_COMBINATION euc | m1_noscratch m1_unlit m1_flat m1_phong m1_wireframe"
    "M3 $DEFAULT_COMBINATION euc | m1_noscratch m1_unlit m1_flat m1_phong m1_wireframe"
    "M4 m4=ours m4_untextured=ours-untextured | m4_bilinear"
)
# The counting program of a mesh scene when it is not count3d: M4's frames live in a program of
# their own so that they do not change how count3d's are compiled.
declare -A MESH_PROGRAM=([M4]=count3d_tex)

# The RAM and code size of M1 configurations, one line each: RENDERER, the configuration as
# tests/tests/stack.rs and scripts/memory.sh name it. The lines before the empty entry are the
# required ones (--quick).
MEMORY_JOBS=(
    "ours gouraud_depth_cull_draw"
    "ours-band16 $BAND16_MEMORY"
    ""
    "ours-m1_noscratch gouraud_depth_cull_noscratch"
    "ours-m1_band16_noscratch gouraud_depth_cull_banded16_noscratch"
)

SCENES_2D=(L1 T1 T2 G1 P1)

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
OUT="$TARGET_DIR/figures"

# usage [STATUS]: the usage lines of the header.
usage() {
    sed -n '/^# Usage/,/^# What/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
    exit "${1:-2}"
}

QUICK=0
FILE="${FIGURES_OUT:-}"
SELECTED=()
while [ "$#" -gt 0 ]; do
    case "$1" in
    --quick) QUICK=1 ;;
    -o)
        [ "$#" -ge 2 ] || usage
        FILE="$2"
        shift
        ;;
    -h | --help) usage 0 ;;
    -*) usage ;;
    *) SELECTED+=("$1") ;;
    esac
    shift
done

# A relative output file is the caller's, not the repository's.
case "$FILE" in
'' | /*) ;;
*) FILE="$PWD/$FILE" ;;
esac
cd "$ROOT"

# Every scene this script knows, in output order.
ALL_SCENES=("${SCENES_2D[@]}" LIMIT)
for line in "${MESH_SCENES[@]}"; do ALL_SCENES+=("${line%% *}"); done
ALL_SCENES+=(S1 I1)
declare -A WANT
if [ "${#SELECTED[@]}" -eq 0 ]; then
    for s in "${ALL_SCENES[@]}"; do WANT[$s]=1; done
else
    for s in "${SELECTED[@]}"; do
        case " ${ALL_SCENES[*]} " in
        *" $s "*) WANT[$s]=1 ;;
        *)
            echo "figures.sh: unknown scene $s (known: ${ALL_SCENES[*]})" >&2
            exit 2
            ;;
        esac
    done
    # T2's share of LIMIT needs LIMIT's count from the same run.
    if [ -n "${WANT[T2]:-}" ]; then WANT[LIMIT]=1; fi
fi
wanted() { [ -n "${WANT[$1]:-}" ]; }

# shellcheck source=lib/callgrind-common.sh
source "$ROOT/scripts/lib/callgrind-common.sh"
# shellcheck source=lib/memory-common.sh
source "$ROOT/scripts/lib/memory-common.sh"

START=$SECONDS
mkdir -p "$OUT"
ROWS="$OUT/figures.tsv.partial"
: >"$ROWS"

# emit SCENE RENDERER METRIC VALUE: one line of the output. Values must be plain numbers.
emit() {
    case "$4" in
    '' | *[!0-9.]* | *.*.* | .* | *.)
        echo "figures.sh: $1 $2 $3: not a plain number: '$4'" >&2
        exit 1
        ;;
    esac
    printf '%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" >>"$ROWS"
}

# emit_count SCENE RENDERER METRIC VALUE: as emit, for a figure that cannot be zero.
emit_count() {
    if ! awk -v v="$4" 'BEGIN { exit !(v + 0 > 0) }' 2>/dev/null; then
        echo "figures.sh: $1 $2 $3 is '$4': missing or zero" >&2
        exit 1
    fi
    emit "$@"
}

# div A B DECIMALS: A / B rounded.
div() { awk -v a="$1" -v b="$2" -v d="$3" 'BEGIN { if (b == 0) exit 1; printf "%.*f", d, a / b }'; }

# field FILE KEY: the value of KEY=value in FILE's last line that has it.
field() {
    local v
    v="$(sed -n "s/.*[ ]$2=\([0-9.]*\).*/\1/p; s/^$2=\([0-9.]*\).*/\1/p" "$1" | tail -n 1)"
    if [ -z "$v" ]; then
        echo "figures.sh: no $2= in $1" >&2
        exit 1
    fi
    echo "$v"
}

ensure_valgrind

# --- 2D scenes and LIMIT (count2d) ---

need_2d=0
for s in "${SCENES_2D[@]}" LIMIT; do wanted "$s" && need_2d=1; done
if [ "$need_2d" = 1 ]; then
    build_example count2d
    COUNT2D="$BIN"
fi

# count2d_frame SCENE RENDERER FRAME_FN: counts one frame; prints its instructions.
count2d_frame() {
    echo "counting $1 $2..." >&2
    callgrind_count "$OUT/$1-$2" "*${3}*" "$COUNT2D" "$1" "$2"
}

declare -A INSTR2D PIXELS2D
if wanted LIMIT; then
    LIMIT_INSTR="$(count2d_frame LIMIT ours frame_limit)"
    "$COUNT2D" LIMIT ours --stats >"$OUT/LIMIT-stats.txt"
    LIMIT_PIXELS="$(field "$OUT/LIMIT-stats.txt" pixels)"
fi
for scene in "${SCENES_2D[@]}"; do
    wanted "$scene" || continue
    renderers=(ours eg)
    case "$scene" in
    L1) kind=lines ;;
    G1)
        kind=gouraud
        renderers=(ours) # embedded-graphics has no Gouraud fill
        ;;
    P1)
        kind=polygons
        renderers=(ours) # nor a polygon fill
        ;;
    *) kind=triangles ;;
    esac
    for r in "${renderers[@]}"; do
        n="$(count2d_frame "$scene" "$r" "frame_${r}_$kind")"
        prims="$(field "$OUT/$scene-$r.stdout" primitives)"
        "$COUNT2D" "$scene" "$r" --stats >"$OUT/$scene-$r-stats.txt"
        px="$(field "$OUT/$scene-$r-stats.txt" pixels)"
        INSTR2D[$scene.$r]=$n
        PIXELS2D[$scene.$r]=$px
        emit_count "$scene" "$r" instructions "$n"
        emit_count "$scene" "$r" primitives "$prims"
        emit_count "$scene" "$r" per_primitive "$(div "$n" "$prims" 1)"
        emit_count "$scene" "$r" pixels "$px"
        emit_count "$scene" "$r" spans "$(field "$OUT/$scene-$r-stats.txt" spans)"
    done
    if [ "$scene" = T2 ]; then
        # Pixels per instruction over LIMIT's.
        for r in "${renderers[@]}"; do
            share="$(awk -v p="${PIXELS2D[$scene.$r]}" -v i="${INSTR2D[$scene.$r]}" \
                -v lp="$LIMIT_PIXELS" -v li="$LIMIT_INSTR" 'BEGIN { printf "%.4f", (p / i) / (lp / li) }')"
            emit_count "$scene" "$r" limit_share "$share"
        done
    fi
    if [ -n "${INSTR2D[$scene.eg]:-}" ]; then
        emit_count "$scene" ours/eg ratio "$(div "${INSTR2D[$scene.ours]}" "${INSTR2D[$scene.eg]}" 4)"
    fi
    if [ "$scene" = L1 ] && [ "$QUICK" = 0 ]; then
        # The same lines anti-aliased (draw_line_aa, width 1) against embedded-graphics' line of
        # the same width, counted by a binary of their own (count2d_aa) so count2d stays as it
        # was; no pixel figures (a counting target cannot read back).
        build_example count2d_aa
        echo "counting L1 ours-aa..." >&2
        n="$(callgrind_count "$OUT/L1-ours-aa" "*frame_ours_aa_lines*" "$BIN")"
        prims="$(field "$OUT/L1-ours-aa.stdout" primitives)"
        emit_count L1 ours-aa instructions "$n"
        emit_count L1 ours-aa per_primitive "$(div "$n" "$prims" 1)"
        emit_count L1 ours-aa/eg ratio "$(div "$n" "${INSTR2D[L1.eg]}" 4)"
        # The same lines 3 pixels wide: draw_line_aa_wide against embedded-graphics' stroke of
        # width 3 (aliased), both in a binary of their own (count2d_aa_wide).
        build_example count2d_aa_wide
        declare -A W3=()
        for r in ours eg; do
            name="$r-w3"
            [ "$r" = ours ] && name=ours-aa-w3
            echo "counting L1 $name..." >&2
            W3[$r]="$(callgrind_count "$OUT/L1-$name" "*frame_${r}_*w3_lines*" "$BIN" "$r")"
            prims="$(field "$OUT/L1-$name.stdout" primitives)"
            emit_count L1 "$name" instructions "${W3[$r]}"
            emit_count L1 "$name" per_primitive "$(div "${W3[$r]}" "$prims" 1)"
        done
        emit_count L1 ours-aa-w3/eg-w3 ratio "$(div "${W3[ours]}" "${W3[eg]}" 4)"
        unset W3
    fi
done
if wanted LIMIT; then
    emit_count LIMIT limit instructions "$LIMIT_INSTR"
    emit_count LIMIT limit pixels "$LIMIT_PIXELS"
fi

# --- Mesh scenes (count3d) ---

declare -A MESH_BIN=()
for line in "${MESH_SCENES[@]}"; do
    scene="${line%% *}"
    wanted "$scene" || continue
    program="${MESH_PROGRAM[$scene]:-count3d}"
    if [ -z "${MESH_BIN[$program]:-}" ]; then
        build_example "$program"
        MESH_BIN[$program]="$BIN"
    fi
done

# renderer_of COMBINATION: the renderer name of a count3d combination.
renderer_of() {
    case "$1" in
    "$DEFAULT_COMBINATION") echo ours ;;
    "$PHONG_COMBINATION") echo ours-phong ;;
    "$BAND16_COMBINATION") echo ours-band16 ;;
    euc) echo euc ;;
    *) echo "ours-$1" ;;
    esac
}

for line in "${MESH_SCENES[@]}"; do
    scene="${line%% *}"
    wanted "$scene" || continue
    jobs="${line#* }"
    required="${jobs%%|*}"
    extra=""
    [[ "$jobs" == *"|"* ]] && extra="${jobs#*|}"
    [ "$QUICK" = 1 ] && extra=""
    COUNT3D="${MESH_BIN[${MESH_PROGRAM[$scene]:-count3d}]}"
    declare -A SCENE_INSTR=()
    # shellcheck disable=SC2086 # the job lists are words
    for job in $required $extra; do
        combo="${job%%=*}"
        if [[ "$job" == *=* ]]; then r="${job#*=}"; else r="$(renderer_of "$combo")"; fi
        echo "counting $scene $combo ($r)..." >&2
        base="$OUT/3d-$scene-$combo"
        n="$(callgrind_count "$base" "*::frame_${combo}*" "$COUNT3D" --scene "$scene" "$combo")"
        tris="$(field "$base.stdout" triangles)"
        drawn="$(field "$base.stdout" drawn)"
        SCENE_INSTR[$r]=$n
        emit_count "$scene" "$r" instructions "$n"
        emit_count "$scene" "$r" per_primitive "$(div "$n" "$tris" 1)"
        emit_count "$scene" "$r" triangles "$tris"
        emit_count "$scene" "$r" drawn "$drawn"
        emit "$scene" "$r" culled "$(field "$base.stdout" culled)"
        emit_count "$scene" "$r" per_drawn "$(div "$n" "$drawn" 1)"
        emit_count "$scene" "$r" covered "$(field "$base.stdout" covered)"
    done
    if [ -n "${SCENE_INSTR[ours]:-}" ] && [ -n "${SCENE_INSTR[ours-untextured]:-}" ]; then
        emit_count "$scene" ours/ours-untextured ratio \
            "$(div "${SCENE_INSTR[ours]}" "${SCENE_INSTR[ours-untextured]}" 4)"
    fi
    if [ "$scene" = M1 ] && [ "$QUICK" = 0 ]; then
        # M1 drawn through Translucent at opacity 128, in a binary of its own
        # (count3d_translucent) so count3d stays as it was: with the writing depth buffer (the
        # pixels of `ours`, each blended) and read-only over a cleared buffer.
        build_example count3d_translucent
        for combo in m1_translucent m1_translucent_readonly; do
            r="ours-$combo"
            echo "counting M1 $combo ($r)..." >&2
            base="$OUT/3d-M1-$combo"
            n="$(callgrind_count "$base" "*::frame_${combo}*" "$BIN" "$combo")"
            drawn="$(field "$base.stdout" drawn)"
            emit_count M1 "$r" instructions "$n"
            emit_count M1 "$r" per_primitive "$(div "$n" "$(field "$base.stdout" triangles)" 1)"
            emit_count M1 "$r" drawn "$drawn"
            emit_count M1 "$r" per_drawn "$(div "$n" "$drawn" 1)"
            emit_count M1 "$r" covered "$(field "$base.stdout" covered)"
            if [ -n "${SCENE_INSTR[ours]:-}" ]; then
                emit_count M1 "$r/ours" ratio "$(div "$n" "${SCENE_INSTR[ours]}" 4)"
            fi
        done
    fi
    if [ -n "${SCENE_INSTR[ours]:-}" ] && [ -n "${SCENE_INSTR[euc]:-}" ]; then
        emit_count "$scene" ours/euc ratio "$(div "${SCENE_INSTR[ours]}" "${SCENE_INSTR[euc]}" 4)"
        if [ "$QUICK" = 0 ]; then
            # count3d compare draws count3d's m1 and euc.
            echo "comparing $scene pictures..." >&2
            "$COUNT3D" --scene "$scene" compare >"$OUT/3d-$scene-compare.txt"
            cmp="$OUT/3d-$scene-compare.txt"
            emit_count "$scene" ours/euc pixels_both "$(field "$cmp" both)"
            emit "$scene" ours/euc pixels_ours_only "$(field "$cmp" ours_only)"
            emit "$scene" ours/euc pixels_euc_only "$(field "$cmp" euc_only)"
            emit "$scene" ours/euc mean_channel_diff "$(field "$cmp" mean_diff)"
            emit "$scene" ours/euc max_channel_diff "$(field "$cmp" max_diff)"
            emit "$scene" ours/euc pixels_over_16 "$(field "$cmp" over_16)"
        fi
    fi
    unset SCENE_INSTR
done
if wanted M1 && [ "$QUICK" = 0 ]; then
    # M1 with linear fog around the default pipeline's shading, counted by a binary of its own
    # (count3d_fog) so count3d stays as it was.
    build_example count3d_fog
    echo "counting M1 ours-fog..." >&2
    n="$(callgrind_count "$OUT/3d-M1-fog" "*frame_m1_fog*" "$BIN")"
    emit_count M1 ours-fog instructions "$n"
    emit_count M1 ours-fog per_primitive "$(div "$n" "$(field "$OUT/3d-M1-fog.stdout" triangles)" 1)"
    emit_count M1 ours-fog covered "$(field "$OUT/3d-M1-fog.stdout" covered)"
fi

# --- 64-bit divisions and wide products per frame (count-wide build) ---

# The same frames from binaries built with host-tools' `count-wide` feature, which keeps every
# 64-bit (and wider) division and every 64 x 64 -> 128-bit product of the core's triangle work
# out of line in rasterizer-core's `wide` module: the calls to it are the divisions a Cortex-M
# pays a library call for (`div64`) and the products it pays four multiplies for (`mul64`). Its
# instruction counts are not figures.
DIV64_JOBS=(
    "M1 count3d m1 --scene M1 m1"
    "M2 count3d m1 --scene M2 m1"
    "M4 count3d_tex m4 --scene M4 m4"
    "G1 count2d ours_gouraud G1 ours"
)
WIDE_DIV='^rasterizer_core::wide::div'
WIDE_MUL='^rasterizer_core::wide::mul'
declare -A WIDE_BIN=()
for job in "${DIV64_JOBS[@]}"; do
    read -r scene program frame args <<<"$job"
    wanted "$scene" || continue
    if [ -z "${WIDE_BIN[$program]:-}" ]; then
        build_example_with count-wide "$program"
        WIDE_BIN[$program]="$BIN"
    fi
    echo "counting $scene div64 and mul64..." >&2
    base="$OUT/div64-$scene"
    # shellcheck disable=SC2086 # the arguments are words
    DUMP_INSTR=1 callgrind_count "$base" "*frame_${frame}*" "${WIDE_BIN[$program]}" $args >/dev/null
    calls="$(callgrind_entries "$base.out" "${WIDE_BIN[$program]}" "$WIDE_DIV")"
    # Zero is the goal, so it is a valid figure; the routing itself is checked by the count
    # of a scene that still divides (M4's textured pixels) coming out non-zero.
    emit "$scene" ours div64 "$calls"
    emit "$scene" ours mul64 "$(callgrind_entries "$base.out" "${WIDE_BIN[$program]}" "$WIDE_MUL")"
done

if wanted M1; then
    # M1 with perspective-correct colours (numerics::Perspective), counted by a binary of its own
    # (count3d_perspective) so count3d stays as it was.
    build_example count3d_perspective
    echo "counting M1 ours-perspective..." >&2
    n="$(callgrind_count "$OUT/3d-M1-perspective" "*frame_m1_perspective*" "$BIN")"
    emit_count M1 ours-perspective instructions "$n"
    emit_count M1 ours-perspective per_primitive "$(div "$n" "$(field "$OUT/3d-M1-perspective.stdout" triangles)" 1)"
    emit_count M1 ours-perspective covered "$(field "$OUT/3d-M1-perspective.stdout" covered)"
    m1="$(awk -F'\t' '$1 == "M1" && $2 == "ours" && $3 == "instructions" { print $4 }' "$ROWS")"
    if [ -n "$m1" ]; then
        emit_count M1 ours-perspective/ours ratio "$(div "$n" "$m1" 4)"
    fi
    # M1 with MatCap shading per vertex (shade::MatCap, the default image), counted by a binary
    # of its own (count3d_matcap) so count3d stays as it was.
    build_example count3d_matcap
    echo "counting M1 ours-matcap..." >&2
    n="$(callgrind_count "$OUT/3d-M1-matcap" "*frame_m1_matcap*" "$BIN")"
    emit_count M1 ours-matcap instructions "$n"
    emit_count M1 ours-matcap per_primitive "$(div "$n" "$(field "$OUT/3d-M1-matcap.stdout" triangles)" 1)"
    emit_count M1 ours-matcap covered "$(field "$OUT/3d-M1-matcap.stdout" covered)"
    if [ -n "$m1" ]; then
        emit_count M1 ours-matcap/ours ratio "$(div "$n" "$m1" 4)"
    fi
    # M1 with anti-aliased silhouettes (Pipeline::draw_antialiased, adjacency by position),
    # counted by a binary of its own (count3d_aa) so count3d stays as it was.
    build_example count3d_aa
    echo "counting M1 ours-aa..." >&2
    n="$(callgrind_count "$OUT/3d-M1-aa" "*frame_m1_aa*" "$BIN")"
    emit_count M1 ours-aa instructions "$n"
    emit_count M1 ours-aa per_primitive "$(div "$n" "$(field "$OUT/3d-M1-aa.stdout" triangles)" 1)"
    emit_count M1 ours-aa covered "$(field "$OUT/3d-M1-aa.stdout" covered)"
    if [ -n "$m1" ]; then
        emit_count M1 ours-aa/ours ratio "$(div "$n" "$m1" 4)"
    fi
fi

# --- RAM and code size of M1 (stack test, nostd-check) ---

if wanted M1; then
    log="$OUT/stack-release.log"
    stack_test release "$log"
    declare -A MEM=()
    read_memory "$log" MEM release
    # m KEY: KEY of the current configuration's MEMORY line.
    m() { echo "${MEM[release.$config.$1]}"; }
    for job in "${MEMORY_JOBS[@]}"; do
        if [ -z "$job" ]; then
            [ "$QUICK" = 1 ] && break
            continue
        fi
        r="${job%% *}"
        config="${job#* }"
        # A missing key would only fail inside a command substitution, which does not stop the
        # script: check every key here.
        for key in stack depth band band_depth bins visible scratch pipeline framebuffer; do
            if [ -z "${MEM[release.$config.$key]:-}" ]; then
                echo "figures.sh: the stack test printed no $key for $config (see $log)" >&2
                exit 1
            fi
        done
        # Everything the frame needs besides the mesh and the output (the framebuffer).
        ram=0
        for part in depth band band_depth bins scratch stack; do ram=$((ram + $(m "$part"))); done
        emit_count M1 "$r" ram_bytes "$ram"
        emit M1 "$r" depth_bytes "$(m depth)"
        emit M1 "$r" band_bytes "$(m band)"
        emit M1 "$r" band_depth_bytes "$(m band_depth)"
        emit M1 "$r" bins_bytes "$(m bins)"
        emit M1 "$r" binned_triangles "$(m visible)"
        emit M1 "$r" scratch_bytes "$(m scratch)"
        emit_count M1 "$r" stack_bytes "$(m stack)"
        emit_count M1 "$r" pipeline_bytes "$(m pipeline)"
        emit M1 "$r" framebuffer_bytes "$(m framebuffer)"
        nostd_build "$config"
        emit_count M1 "$r" text_bytes "$(section_bytes "$config" text)"
        emit_count M1 "$r" rodata_bytes "$(section_bytes "$config" rodata)"
        emit_count M1 "$r" text_bytes_thumbv7em "$(thumb_text_bytes "$config")"
    done
fi

# --- S1: a firmware screen through the frame list (count_s1, stack test, nostd-check) ---

if wanted S1; then
    build_example count_s1
    declare -A S1=()
    for mode in s1 s1_band16 s1_band16x2 s1_region; do
        echo "counting S1 $mode..." >&2
        S1[$mode]="$(callgrind_count "$OUT/S1-$mode" "*frame_$mode" "$BIN" "$mode")"
    done
    # The banded frames are the whole frame's picture (the tests check the region's).
    s1_sum() { sed -n 's/.* checksum=\([0-9a-f]*\).*/\1/p' "$OUT/S1-$1.stdout" | tail -n 1; }
    for mode in s1_band16 s1_band16x2; do
        if [ -z "$(s1_sum s1)" ] || [ "$(s1_sum "$mode")" != "$(s1_sum s1)" ]; then
            echo "figures.sh: S1 $mode draws another picture than the whole frame" >&2
            exit 1
        fi
    done
    emit_count S1 ours instructions "${S1[s1]}"
    emit_count S1 ours-band16 instructions "${S1[s1_band16]}"
    emit_count S1 ours-band16x2 instructions "${S1[s1_band16x2]}"
    emit_count S1 ours-region instructions "${S1[s1_region]}"
    emit_count S1 ours-region pixels "$(field "$OUT/S1-s1_region.stdout" pixels)"
    emit_count S1 ours-band16/ours ratio "$(div "${S1[s1_band16]}" "${S1[s1]}" 4)"
    emit_count S1 ours-band16x2/ours ratio "$(div "${S1[s1_band16x2]}" "${S1[s1]}" 4)"
    emit_count S1 ours-region/ours ratio "$(div "${S1[s1_region]}" "${S1[s1]}" 4)"
    # RAM besides the meshes, font and output: band buffers, band depth, bins, vertex scratch and
    # the peak stack of building and rendering the list (its slots and mesh commands included).
    log="$OUT/stack-s1-release.log"
    stack_test release "$log" stack_s1
    declare -A MEM_S1=()
    read_memory "$log" MEM_S1 release
    for config in s1_band16 s1_band16x2; do
        r="ours-${config#s1_}"
        for key in stack band band_depth bins scratch; do
            if [ -z "${MEM_S1[release.$config.$key]:-}" ]; then
                echo "figures.sh: the stack test printed no $key for $config (see $log)" >&2
                exit 1
            fi
        done
        ram=0
        for part in band band_depth bins scratch stack; do ram=$((ram + MEM_S1[release.$config.$part])); done
        emit_count S1 "$r" ram_bytes "$ram"
        emit S1 "$r" band_bytes "${MEM_S1[release.$config.band]}"
        emit S1 "$r" band_depth_bytes "${MEM_S1[release.$config.band_depth]}"
        emit S1 "$r" bins_bytes "${MEM_S1[release.$config.bins]}"
        emit S1 "$r" scratch_bytes "${MEM_S1[release.$config.scratch]}"
        emit_count S1 "$r" stack_bytes "${MEM_S1[release.$config.stack]}"
    done
    nostd_build s1_band16
    emit_count S1 ours-band16 text_bytes "$(section_bytes s1_band16 text)"
    emit_count S1 ours-band16 text_bytes_thumbv7em "$(thumb_text_bytes s1_band16)"
    emit_count S1 ours-band16 rodata_bytes "$(section_bytes s1_band16 rodata)"
    unset S1 MEM_S1
fi

# --- I1: sprites, and I1id against embedded-graphics' Image (count_i1) ---

if wanted I1; then
    build_example count_i1
    declare -A I1N=()
    for job in ours=frame_i1_ours ours-id=frame_i1id_ours eg-id=frame_i1id_eg; do
        r="${job%%=*}"
        echo "counting I1 $r..." >&2
        I1N[$r]="$(callgrind_count "$OUT/I1-$r" "*${job#*=}*" "$BIN" "$r")"
    done
    prims="$(field "$OUT/I1-ours.stdout" primitives)"
    "$BIN" ours --stats >"$OUT/I1-ours-stats.txt"
    emit_count I1 ours instructions "${I1N[ours]}"
    emit_count I1 ours per_primitive "$(div "${I1N[ours]}" "$prims" 1)"
    emit_count I1 ours pixels "$(field "$OUT/I1-ours-stats.txt" pixels)"
    for r in ours eg; do
        emit_count I1id "$r" instructions "${I1N[$r-id]}"
        emit_count I1id "$r" per_primitive "$(div "${I1N[$r-id]}" "$prims" 1)"
    done
    emit_count I1id ours/eg ratio "$(div "${I1N[ours-id]}" "${I1N[eg-id]}" 4)"
    unset I1N
fi

if [ -n "$FILE" ]; then
    cp "$ROWS" "$FILE.tmp"
    mv "$FILE.tmp" "$FILE"
    echo "wrote $FILE" >&2
fi
cat "$ROWS"
echo "figures.sh: $(wc -l <"$ROWS") figures in $((SECONDS - START)) s" >&2
