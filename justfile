# wingcheck recipes (https://github.com/casey/just); plain cargo commands work just as well.

default: test

fmt:
    cargo fmt --all

clippy:
    cargo clippy --workspace --all-targets -- -D warnings

test:
    cargo test --workspace --release

ci:
    bash .ci/run

bench:
    cargo run --release -- bench

report:
    cargo run --release -- report

check:
    cargo run --release -- check

# Render the report with headless Chromium (apt-get install chromium) for a person to look at.
screenshot:
    chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking --disable-component-update --disable-sync --user-data-dir=$(mktemp -d) --window-size=1400,4000 --screenshot=reports/paper/screenshot.png reports/paper/index.html
