#!/usr/bin/env bash
# CI steps for the Python package `candela` (crates/candela-py), for .ci/run:
#   bash crates/candela-py/ci-steps.sh
# Needs python3 (3.9+) with pip, and cargo. Installs the Python test
# dependencies, lints the crate (its own workspace: see its Cargo.toml), builds
# and installs the wheel, builds the CLI for the CLI-equality test, and runs
# pytest (about 10 s of tests after the builds). The denoising tests, Rust and
# Python, must find Open Image Denoise here (CANDELA_REQUIRE_OIDN=1).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD

python3 -m pip install --quiet -r crates/candela-py/requirements-dev.txt

# Open Image Denoise came with pyoidn (requirements-dev.txt): from here on a
# denoising test that cannot load it fails instead of skipping. `.ci/run`
# sets the same before the README's test command, so there the Rust
# denoising tests have run with the library already; run alone, this script
# runs them here.
export CANDELA_REQUIRE_OIDN=1
if [ -z "${CANDELA_OIDN_LIB:-}" ]; then
    CANDELA_OIDN_LIB="$(python3 -c 'import importlib.util as u, os; print(os.path.join(os.path.dirname(u.find_spec("pyoidn").origin), "oidn", "lib"))')"
    export CANDELA_OIDN_LIB
    cargo test -p candela-image --lib denoise
    cargo test -p candela-render --test denoise
    cargo test -p candela-cli --test denoise_cli
fi

cargo fmt --manifest-path crates/candela-py/Cargo.toml -p candela-py -- --check
cargo clippy --manifest-path crates/candela-py/Cargo.toml --all-targets -- -D warnings

# The wheel: release, but without fat LTO to keep CI within its time.
rm -rf crates/candela-py/dist
CARGO_PROFILE_RELEASE_LTO=off CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 \
    python3 -m maturin build --release -i python3 -o crates/candela-py/dist \
    --manifest-path crates/candela-py/Cargo.toml
python3 -m pip install --quiet --force-reinstall --no-deps crates/candela-py/dist/candela-*.whl

# The CLI, in the test profile that `cargo test --workspace` already built.
CANDELA_BIN="$(bash .ci/cli-binary.sh)"
export CANDELA_BIN
if [ -d "$root/../shared/scenes/cs184" ]; then
    export CANDELA_SCENES="$root/../shared/scenes/cs184"
fi

cd crates/candela-py
python3 -m pytest tests -q -p no:cacheprovider
