#!/usr/bin/env bash
# Renders the README's pictures: every seed space's default view through the GPU tracer (the
# plugin offscreen; lavapipe where there is no GPU), and a window screenshot with the panel.
# Usage: scripts/render-gallery.sh [WIDTHxHEIGHT]   (default 480x270; files in docs/images/)
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-480x270}"
scripts/setup-system.sh
cargo build --quiet
bin=./target/debug/curved-spaces
mkdir -p docs/images
# The seed spaces (the first block of `list`), then a few spaces from groups.
seeds=$($bin list | awk 'NR > 1 && NF == 0 { exit } NR > 1 { print $1 }')
for space in $seeds weeks census-10 lens-7-2 prism-5 binary-octahedral second-amphidicosm lens-7-1 \
    projective-space; do
    $bin render "$space" --size "$size" --out "docs/images/$space.png"
done
# The app itself, panel shown, in a virtual X display when there is none.
if command -v xvfb-run >/dev/null 2>&1; then
    xvfb-run -a -s "-screen 0 1280x720x24" $bin walk poincare --screenshot docs/images/walk-panel.png
else
    echo "note: xvfb-run not found (apt-get install xvfb); skipping the window screenshot" >&2
fi
