#!/usr/bin/env bash
# Quick start: builds and runs the app (release). With no arguments it renders the default
# space, Seifert–Weber, to curved-spaces.png and says where; arguments go to curved-spaces
# (try `scripts/run.sh --help`).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-system.sh
exec cargo run --release --quiet -- "$@"
