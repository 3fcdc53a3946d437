#!/usr/bin/env bash
# Quick start: installs what is missing, then runs every test (unit, integration, CLI,
# doctests) and builds the examples. Arguments go to `cargo test`.
#
# Same profile as scripts/run.sh, so the two share one build.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-system.sh
# GPU renders on a headless machine: a private runtime folder keeps the Vulkan loader's Wayland
# client from printing `XDG_RUNTIME_DIR is invalid or not set` for every render (the app does
# the same for itself).
if [ ! -d "${XDG_RUNTIME_DIR:-}" ]; then
    XDG_RUNTIME_DIR="$(mktemp -d -t curved-spaces-runtime.XXXXXX)"
    export XDG_RUNTIME_DIR
fi
exec cargo test "$@"
