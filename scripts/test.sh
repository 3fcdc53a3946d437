#!/usr/bin/env bash
# Quick start: installs what is missing, then runs every test (unit, integration, CLI,
# doctests) and builds the examples.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-system.sh
exec cargo test "$@"
