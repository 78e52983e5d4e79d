# Shared by scripts/callgrind.sh and scripts/callgrind3d.sh (sourced, not run).

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
    BIN="$TARGET_DIR/release/examples/$1"
}
