# shellcheck shell=bash
# Shared by scripts/memory.sh and scripts/figures.sh (sourced, not run): the code size of one
# configuration (a nostd-check build) and the RAM figures tests/tests/stack.rs prints.
# The caller sets ROOT (the repository) and TARGET_DIR (the cargo target directory).

# nostd-check is its own workspace; its variants are built here, apart from the main workspace's
# builds and from the nostd-check/target that .ci/run uses.
NOSTD_DIR="$TARGET_DIR/nostd-variants"

# features_of CONFIGURATION: the nostd-check features of a configuration named as the stack test
# names it (SHADING_DEPTH_CULL_MODE[_noscratch], or a 2D primitive; `all` and `empty` have none).
features_of() {
    case "$1" in
    line) echo line2d ;;
    triangle) echo triangle2d ;;
    gouraud_triangle) echo gouraud2d ;;
    polygon) echo polygon2d ;;
    empty | all) echo "" ;;
    # Workload S1 through the frame list in 16-row bands, one band buffer or two.
    s1_band16) echo framelist ;;
    s1_band16x2) echo framelist,double ;;
    *)
        local IFS=_ f
        # shellcheck disable=SC2086 # split the name at its underscores
        set -- $1
        f="$1"
        [ "$2" = depth ] && f="$f,depth"
        [ "$3" = cull ] && f="$f,cull"
        case "$4" in
        noscratch) f="$f,noscratch" ;;
        banded16) f="$f,banded" ;;
        esac
        [ "${5:-}" = noscratch ] && f="$f,noscratch"
        echo "$f"
        ;;
    esac
}

# nostd_cargo_build NAME [CARGO ARGS...]: builds configuration NAME of nostd-check (`all`: the
# default features, every entry point) in release into $NOSTD_DIR, with the extra cargo
# arguments given (a target). RUSTFLAGS is cleared, as for the counts.
nostd_cargo_build() {
    local name="$1" features args=()
    shift
    features="$(features_of "$name")"
    if [ "$name" != all ]; then
        args=(--no-default-features)
        [ -n "$features" ] && args+=(--features "$features")
    fi
    echo "nostd-check $name (${features:-default features})${*:+ $*}" >&2
    (cd "$ROOT/nostd-check" && CARGO_TARGET_DIR="$NOSTD_DIR" RUSTFLAGS="" cargo build --quiet --release "${args[@]}" "$@")
}

# nostd_build NAME: builds the nostd-check variant of configuration NAME, keeps it as
# $NOSTD_DIR/bin/NAME and runs it: a 3D variant exits non-zero when it drew nothing.
nostd_build() {
    local name="$1"
    nostd_cargo_build "$name" || return 1
    mkdir -p "$NOSTD_DIR/bin"
    cp "$NOSTD_DIR/release/nostd-check" "$NOSTD_DIR/bin/$name"
    if ! "$NOSTD_DIR/bin/$name"; then
        echo "nostd-check $name exited non-zero (drew nothing?)" >&2
        return 1
    fi
}

# The Cortex-M4F target of the flash figures (`text_bytes_thumbv7em`): on it `.text` is what a
# firmware image holds, with the 64-bit arithmetic a 32-bit core does in several instructions
# and the memory routines that the host's C library supplies elsewhere.
THUMB_TARGET=thumbv7em-none-eabihf

# thumb_text_bytes NAME: builds configuration NAME of nostd-check for $THUMB_TARGET (it links
# there but cannot run here), keeps it as $NOSTD_DIR/bin/NAME.$THUMB_TARGET and prints its .text
# size. rustup adds the target's standard library when it is missing.
thumb_text_bytes() {
    local name="$1"
    if ! rustup target list --installed 2>/dev/null | grep -qx "$THUMB_TARGET"; then
        rustup target add "$THUMB_TARGET" >&2 || {
            echo "could not add the $THUMB_TARGET target (rustup target add $THUMB_TARGET)" >&2
            return 1
        }
    fi
    nostd_cargo_build "$name" --target "$THUMB_TARGET" || return 1
    mkdir -p "$NOSTD_DIR/bin"
    cp "$NOSTD_DIR/$THUMB_TARGET/release/nostd-check" "$NOSTD_DIR/bin/$name.$THUMB_TARGET"
    section_bytes "$name.$THUMB_TARGET" text
}

# section_bytes NAME SECTION: the size of SECTION (text, rodata, data, bss) of a variant that
# nostd_build built; 0 when the binary has no such section.
section_bytes() {
    command -v size >/dev/null || {
        echo "needs size (binutils)" >&2
        return 1
    }
    local bytes
    bytes="$(size -A "$NOSTD_DIR/bin/$1" | awk -v s=".$2" '$1 == s { print $2 }')"
    echo "${bytes:-0}"
}

# stack_test PROFILE LOG [FILTER]: runs tests/tests/stack.rs (PROFILE release or debug) with its
# output in LOG; FILTER picks some of its tests. Fails, pointing at LOG, when the test fails.
stack_test() {
    local profile="$1" log="$2" args=() filter=()
    [ "$profile" = release ] && args=(--release)
    [ -n "${3:-}" ] && filter=("$3")
    echo "stack test ($profile${3:+, $3})" >&2
    if ! (cd "$ROOT" && CARGO_TARGET_DIR="$TARGET_DIR" RUSTFLAGS="" cargo test --quiet "${args[@]}" \
        -p tests --test stack -- --nocapture --test-threads=1 "${filter[@]}" >"$log" 2>&1); then
        echo "the stack test failed ($profile); see $log" >&2
        return 1
    fi
}

# read_memory LOG ARRAY PREFIX: stores each `MEMORY NAME key=value ...` line of LOG in the
# associative array ARRAY as ARRAY[PREFIX.NAME.key]=value.
read_memory() {
    local log="$1" prefix="$3" line name kv
    local -n into="$2"
    while read -r line; do
        # shellcheck disable=SC2086 # split the line into its fields
        set -- $line
        name="$2"
        shift 2
        for kv in "$@"; do
            # shellcheck disable=SC2034 # `into` is the caller's array
            into["$prefix.$name.${kv%%=*}"]="${kv#*=}"
        done
    # The test harness may print "test NAME ... " in front of a test's first line.
    done < <(grep -o 'MEMORY .*' "$log")
}
