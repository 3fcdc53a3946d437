#!/usr/bin/env bash
# The benchmark on a real GPU, in a few minutes: every seed space at 640×360, 1280×720 and
# 1920×1080, crossing budgets 16 and 32, the default scene's edges culled, unculled and
# absent (with the share of segments and of pixel blocks near two faces at once), the
# tracer against a straightforward tracer of the same walk, the work per pixel and ns per
# pixel-crossing. Then the edges of every seed space and of `weeks` (the smallest census
# manifold) at 1920×1080, with the crossings per pixel (mean and p90), ns per
# pixel-segment and what 8×8 tiles could share. Figures go to docs/results/gpu/ (or the
# folder given as the first argument): summary.md, timings.csv, edges.csv, bench.json and
# the charts, and edges-1080p/ with the second run's.
#
# On a machine without a GPU it runs on whatever Vulkan driver there is (lavapipe on the
# CPU), slowly; say which device was measured from the summary's first lines.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-docs/results/gpu}"
scripts/setup-system.sh
# The dev profile is optimised (Cargo.toml) and shared with the tests: one build.
cargo run --quiet -- bench \
    --sizes 640x360,1280x720,1920x1080 \
    --budgets 16,32 \
    --out "$out"
# Every seed space (the first column of `list`, under its header) and weeks.
spaces="$(cargo run --quiet -- list | awk 'NR > 1 && NF == 0 { exit } NR > 1 { print $1 }' | paste -sd,)"
exec cargo run --quiet -- bench --edges \
    --spaces "$spaces,weeks" \
    --sizes 1920x1080 \
    --budgets 24 \
    --out "$out/edges-1080p"
