#!/usr/bin/env bash
# Renders the README's pictures: every seed space's default view, with the CPU reference.
# Usage: scripts/render-gallery.sh [WIDTHxHEIGHT]   (default 480x270; files in docs/images/)
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-480x270}"
cargo build --release --quiet
mkdir -p docs/images
for space in $(./target/release/curved-spaces list | awk 'NR > 1 { print $1 }'); do
    ./target/release/curved-spaces render "$space" --cpu --size "$size" --out "docs/images/$space.png"
done
