#!/usr/bin/env bash
# The benchmark on a real GPU, in a few minutes: every seed space at 640×360, 1280×720 and
# 1920×1080, crossing budgets 16 and 32, the default scene's edges culled, unculled and
# absent (with the share of segments and of pixel blocks near two faces at once), the
# tracer against a straightforward tracer of the same walk, the work per pixel and ns per
# pixel-crossing. Figures go to
# docs/results/gpu/ (or the folder given as the first argument): summary.md, timings.csv,
# edges.csv, bench.json and the charts.
#
# On a machine without a GPU it runs on whatever Vulkan driver there is (lavapipe on the
# CPU), slowly; say which device was measured from the summary's first lines.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-docs/results/gpu}"
scripts/setup-system.sh
# The dev profile is optimised (Cargo.toml) and shared with the tests: one build.
exec cargo run --quiet -- bench \
    --sizes 640x360,1280x720,1920x1080 \
    --budgets 16,32 \
    --out "$out"
