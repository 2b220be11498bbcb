# Sourced by the search scripts: sets $wingcheck to the binary to run, the first of
#   1. $WINGCHECK, if set;
#   2. `wingcheck` on PATH (`cargo install --locked --path .` puts it in ~/.cargo/bin);
#   3. the checkout's release build (`cargo build --release`): $CARGO_TARGET_DIR/release/wingcheck
#      if CARGO_TARGET_DIR is set, else <checkout>/target/release/wingcheck, the checkout being
#      the directory above this file (symbolic links resolved);
# and exits with status 1 and a message saying how to get one if there is none.
find_wingcheck() {
    local here checkout candidate
    if [ -n "${WINGCHECK:-}" ]; then
        wingcheck=$WINGCHECK
        return 0
    fi
    if command -v wingcheck >/dev/null 2>&1; then
        wingcheck=$(command -v wingcheck)
        return 0
    fi
    here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
    checkout=$(dirname "$here")
    candidate=${CARGO_TARGET_DIR:-$checkout/target}/release/wingcheck
    if [ -x "$candidate" ]; then
        wingcheck=$candidate
        return 0
    fi
    echo "error: no wingcheck binary: none on PATH and no $candidate;" \
        "run 'cargo install --locked --path .' (or 'cargo build --release') in $checkout, or set WINGCHECK=/path/to/wingcheck" >&2
    exit 1
}
find_wingcheck
