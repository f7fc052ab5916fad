#!/usr/bin/env bash
# Prints the path of the CLI binary the CI steps and the browser and Python
# tests run: the test profile's (opt-level 3, no LTO), as `cargo test
# --workspace` builds it for the CLI's integration tests. Asking for it the
# same way (`--workspace --no-run`) keeps the workspace's feature set, so
# after the README's test command nothing is compiled again; `cargo build -p
# candela-cli` would resolve features for that package alone and rebuild the
# renderer (about two minutes on CI's two cores).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace --no-run --quiet 1>&2
echo "$PWD/target/debug/candela"
