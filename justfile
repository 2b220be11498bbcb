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

# Regenerate the JSON Schemas of the config and every JSON output (docs/schema/; tests/outputs.rs
# checks the committed ones are current).
schema:
    cargo run --release -- schema --out docs/schema

# Screenshots of the report (top of the page and every section) with headless Chromium, into
# target/screenshots/, for a person to look at. Works without just: scripts/screenshot.sh.
screenshot report="reports/paper" out="target/screenshots":
    bash scripts/screenshot.sh {{report}} {{out}}
