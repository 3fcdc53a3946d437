#!/usr/bin/env bash
# Installs the Debian packages the project needs, if any are missing.
# - mesa-vulkan-drivers, libvulkan1: Vulkan on the CPU (lavapipe) where there is no GPU.
# - libx11-6, libxcursor1, libxrandr2, libxi6, libxkbcommon-x11-0: the window (X11), loaded
#   at run time.
# Runs apt-get as root, or through sudo; says what to do when it can do neither.
set -euo pipefail
packages=(mesa-vulkan-drivers libvulkan1 libx11-6 libxcursor1 libxrandr2 libxi6 libxkbcommon-x11-0)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
if ! command -v apt-get >/dev/null 2>&1; then
    echo "note: not a Debian system; install these yourself if you need GPU renders: ${missing[*]}" >&2
    exit 0
fi
if [ "$(id -u)" -eq 0 ]; then
    sudo=()
elif command -v sudo >/dev/null 2>&1; then
    sudo=(sudo)
else
    echo "error: missing packages ${missing[*]}; run as root: apt-get install ${missing[*]}" >&2
    exit 1
fi
echo "installing ${missing[*]}…" >&2
"${sudo[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
