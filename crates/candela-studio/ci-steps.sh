#!/usr/bin/env bash
# Browser tests of Candela Studio: Debian's chromium driven by Playwright for
# Python (its own browser download is never used). Installs what is missing,
# builds the CLI's test-profile binary if it is not up to date (after the
# README's test command it is), and runs pytest. Run from anywhere:
# bash crates/candela-studio/ci-steps.sh
set -euo pipefail
cd "$(dirname "$0")/../.."

if [ ! -x /usr/bin/chromium ]; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq chromium
fi

venv=target/studio-venv
if ! "$venv/bin/python" -c "import playwright, pytest" 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q playwright pytest
fi

# The test profile's binary, which `cargo test --workspace` has built.
CANDELA_BIN="$(bash .ci/cli-binary.sh)" "$venv/bin/python" -m pytest -q -p no:cacheprovider \
  crates/candela-studio/tests/browser
