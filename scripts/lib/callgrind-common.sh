# shellcheck shell=bash
# Shared by scripts/callgrind.sh, scripts/callgrind3d.sh and scripts/figures.sh (sourced, not run).
# The caller sets TARGET_DIR (the cargo target directory) before calling build_example.

# Installs valgrind with apt-get when it is missing.
ensure_valgrind() {
    if ! command -v valgrind >/dev/null 2>&1; then
        echo "valgrind not found: installing it" >&2
        local sudo=""
        if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
        $sudo apt-get update
        $sudo apt-get install -y valgrind
    fi
}

# build_example NAME: builds host-tools' example NAME with --release and no RUSTFLAGS (so no
# target-cpu=native) into $TARGET_DIR and sets BIN to its path.
build_example() {
    echo "building $1 (release)..." >&2
    RUSTFLAGS="" CARGO_TARGET_DIR="$TARGET_DIR" cargo build --quiet --release -p host-tools --example "$1"
    # shellcheck disable=SC2034 # read by the scripts that source this file
    BIN="$TARGET_DIR/release/examples/$1"
}

# build_example_with FEATURES NAME: build_example with host-tools features FEATURES, into a target
# directory of their own ($TARGET_DIR/features-FEATURES) so that the plain build is untouched;
# sets BIN.
build_example_with() {
    local dir="$TARGET_DIR/features-${1//,/-}"
    echo "building $2 with $1 (release)..." >&2
    RUSTFLAGS="" CARGO_TARGET_DIR="$dir" cargo build --quiet --release -p host-tools --features "$1" --example "$2"
    # shellcheck disable=SC2034 # read by the scripts that source this file
    BIN="$dir/release/examples/$2"
}

# callgrind_entries FILE BINARY REGEX: how often the functions of BINARY whose (demangled) names
# match REGEX were entered in callgrind's output FILE, which must be written with
# --dump-instr=yes: the execution count of each one's first instruction, summed. (A `calls=` line
# is no count of this: callgrind records a call through the GOT, as a generic function
# instantiated in another crate makes it, twice.)
callgrind_entries() {
    nm -C "$2" | awk -v re="$3" '$2 ~ /^[tT]$/ {
            name = $0
            sub(/^[0-9a-f]+ [tT] /, "", name)
            if (name ~ re) print $1
        }' | sort -u | awk '
        function hex(s,   v, i, c) {
            v = 0
            s = tolower(s)
            sub(/^0x/, "", s)
            for (i = 1; i <= length(s); i++) {
                c = index("0123456789abcdef", substr(s, i, 1)) - 1
                v = v * 16 + c
            }
            return v
        }
        FNR == NR { want[hex($1)] = 1; next }
        # Position lines: an address (0x.. absolute, +N/-N relative, * the same), a line
        # number, then the cost. The line after calls= is the call cost: its address counts,
        # its cost does not.
        /^calls=/ { call = 1; next }
        /^[0-9+*-]/ {
            a = $1
            if (a ~ /^0x/) addr = hex(a)
            else if (a ~ /^\+/) addr += substr(a, 2) + 0
            else if (a ~ /^-/) addr -= substr(a, 2) + 0
            if (call) { call = 0; next }
            if (addr in want) total += $NF
            next
        }
        END { printf "%d\n", total }
    ' - "$1"
}

# callgrind_count BASE PATTERN COMMAND...: runs COMMAND under callgrind, collecting only inside the
# functions PATTERN matches (--toggle-collect), and prints the instructions collected. Writes
# BASE.out (callgrind's file), BASE.stdout and BASE.log; with ANNOTATE=1 also
# BASE.annotate.txt. Fails, saying why, when valgrind fails or nothing was collected: a frame
# function that was inlined, merged or renamed collects nothing, and a zero must never pass as a
# figure.
callgrind_count() {
    local base="$1" pattern="$2"
    shift 2
    rm -f "$base.out"
    # DUMP_INSTR=1 keeps per-instruction counts (what callgrind_entries reads).
    local extra=()
    if [ "${DUMP_INSTR:-0}" = "1" ]; then extra+=(--dump-instr=yes); fi
    if ! valgrind --tool=callgrind "${extra[@]}" --toggle-collect="$pattern" --callgrind-out-file="$base.out" \
        "$@" >"$base.stdout" 2>"$base.log"; then
        echo "valgrind failed for: $* (see $base.log)" >&2
        return 1
    fi
    local total
    # Older callgrind versions write only `summary:`; both hold the collected total.
    total="$(awk '/^totals:/ {t = $2} /^summary:/ {s = $2} END {print (t != "" ? t : s)}' "$base.out")"
    case "$total" in
    '' | *[!0-9]* | 0)
        echo "no instructions collected for: $* (pattern '$pattern'): was the frame function inlined, merged or renamed?" >&2
        return 1
        ;;
    esac
    if [ "${ANNOTATE:-0}" = "1" ]; then
        callgrind_annotate --auto=yes --inclusive=no "$base.out" >"$base.annotate.txt" 2>/dev/null || true
    fi
    echo "$total"
}
