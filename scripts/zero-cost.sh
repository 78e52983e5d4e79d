#!/usr/bin/env bash
# Checks that code compiled in but not used costs no flash: the M1 configuration of nostd-check
# (Gouraud, depth buffer, back-face culling; `--no-default-features --features gouraud,depth,cull`)
# is built with and without rasterizer-core's `float` feature, its only cargo feature (the f32
# comparison backend, which M1 never calls), and the two binaries must have byte-identical sizes of
# .text, .rodata, .data and .bss. The other optional stages (fog, dither, translucency, textures,
# anti-aliasing) are generic types chosen at the call, not cargo features: a build that does not
# name them cannot contain them, and their cost when used is what scripts/memory.sh measures.
#
# Usage: scripts/zero-cost.sh   (two release builds of nostd-check, about 30 s each on 2 cores)
# Honours CARGO_TARGET_DIR (default: nostd-check/target, as .ci/run).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT/nostd-check"
bin="${CARGO_TARGET_DIR:-$ROOT/nostd-check/target}/release/nostd-check"
base=(--release --no-default-features --features "gouraud,depth,cull")

command -v size >/dev/null || {
    echo "zero-cost.sh: needs size (binutils)" >&2
    exit 1
}

sections() { size -A "$1" | awk '$1 ~ /^\.(text|rodata|data|bss)$/ { print $1, $2 }'; }

cargo build "${base[@]}"
"$bin"
without=$(sections "$bin")
cargo build "${base[@]}" --features rasterizer-core/float
"$bin"
with=$(sections "$bin")

echo "M1 without rasterizer-core/float: $(echo "$without" | tr '\n' ' ')"
echo "M1 with rasterizer-core/float:    $(echo "$with" | tr '\n' ' ')"
if [ "$without" != "$with" ]; then
    echo "zero-cost.sh: the unused float backend changes the M1 binary's sections:" >&2
    diff <(echo "$without") <(echo "$with") >&2 || true
    exit 1
fi
if nm -C "$bin" | grep -qiE 'micromath|math::float'; then
    echo "zero-cost.sh: float backend symbols in the M1 binary built with rasterizer-core/float" >&2
    exit 1
fi
echo "an unused float backend costs nothing: sections identical"
