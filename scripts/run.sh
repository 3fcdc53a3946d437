#!/usr/bin/env bash
# Quick start: builds and runs the app. With no arguments it walks the default space,
# Seifert–Weber, in a window, or (with no display) renders it to curved-spaces.png and says
# where; arguments go to curved-spaces (try `scripts/run.sh --help`).
#
# It builds in the same profile as scripts/test.sh (the dev profile, optimised: see
# Cargo.toml), so running the app and then the tests compiles Bevy once.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-system.sh
exec cargo run --quiet -- "$@"
