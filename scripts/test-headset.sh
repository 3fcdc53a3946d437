#!/usr/bin/env bash
# The headset tests (`cargo test --features xr --test headset`) against a real OpenXR runtime
# with no headset and no display: Monado's service with its null compositor and a simulated
# head-mounted display and controllers. Arguments go to `cargo test`.
#
# Where Monado comes from: Debian 12 packages none, and Debian 13's needs a newer C library
# than this system's. Installing Debian 13's packages would replace the system's C library,
# so instead this script downloads Debian 13's monado-service, its OpenXR client library and
# the OpenXR loader with everything they need that this system lacks (`apt-get download`
# with a private apt configuration: the system's package lists and packages are untouched),
# unpacks them into target/monado/root, and runs both the service and the test binary
# through that folder's own dynamic loader with its libraries first. Building Monado from
# source was the other way; it needs a dozen -dev packages installed in the system and
# ~10 minutes of compiling on two cores, where the download is ~100 MB once and cached:
# a second run needs no network.
#
# The service runs in a private runtime folder, is waited for (its socket), and is stopped
# by its process id when the script ends, also when a test fails.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup-system.sh

base="$PWD/target/monado"
root="$base/root"
packages=(monado-service libopenxr1-monado libopenxr-loader1 libopenxr-dev)
release=trixie
arch=$(dpkg --print-architecture)
triple=$(gcc -dumpmachine 2>/dev/null || echo x86_64-linux-gnu)

fetch_monado() {
    echo "headset tests: fetching Monado and the OpenXR loader from Debian $release into $root (once)…" >&2
    rm -rf "$base/apt" "$base/debs" "$root.partial"
    mkdir -p "$base/apt/none" "$base/apt/lists/partial" "$base/apt/cache/archives/partial" "$base/debs" "$root.partial"
    local mirror
    mirror=$(sed -n 's/^URIs: *\(http[^ ]*\/debian\)$/\1/p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -n 1)
    mirror=${mirror:-http://deb.debian.org/debian}
    echo "deb [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] $mirror $release main" > "$base/apt/sources.list"
    local apt=(
        -o "Dir::Etc::SourceList=$base/apt/sources.list"
        -o "Dir::Etc::SourceParts=$base/apt/none"
        -o "Dir::Etc::Preferences=$base/apt/none"
        -o "Dir::Etc::PreferencesParts=$base/apt/none"
        -o "Dir::State::Lists=$base/apt/lists"
        -o "Dir::Cache=$base/apt/cache"
        -o "Dir::State::status=/var/lib/dpkg/status"
        -o "APT::Architecture=$arch"
        -o "APT::Install-Recommends=false"
        -o "APT::Sandbox::User=root"
        -o "Debug::NoLocking=1"
    )
    apt-get "${apt[@]}" -qq update
    # What installing the packages would bring beside what the system has: the unpacked
    # folder holds those, and the system's own libraries serve the rest.
    local needed
    needed=$(apt-get "${apt[@]}" -s install "${packages[@]}" | sed -n 's/^Inst \([^ ]*\) .*/\1/p')
    if [ -z "$needed" ]; then
        echo "error: apt found nothing to download for ${packages[*]}" >&2
        return 1
    fi
    echo "headset tests: downloading $(echo "$needed" | wc -l) packages…" >&2
    # shellcheck disable=SC2086
    (cd "$base/debs" && apt-get "${apt[@]}" -qq download $needed)
    for deb in "$base"/debs/*.deb; do
        dpkg-deb -x "$deb" "$root.partial"
    done
    rm -rf "$root"
    mv "$root.partial" "$root"
    rm -rf "$base/debs" "$base/apt"
}

if [ ! -x "$root/usr/bin/monado-service" ] || [ ! -e "$root/usr/lib/$triple/libopenxr_loader.so" ]; then
    if [ "$(id -u)" -ne 0 ] && ! command -v apt-get >/dev/null 2>&1; then
        echo "error: the headset tests need Debian's apt-get to fetch Monado" >&2
        exit 1
    fi
    fetch_monado
fi

# Everything runs through the unpacked release's dynamic loader, its libraries first; the
# system's serve what it lacks (among them Mesa's Vulkan driver, lavapipe).
lib="$root/usr/lib/$triple"
library_path="$lib:$root/usr/lib:$lib/lapack:$lib/blas:$lib/pulseaudio:/usr/lib/$triple:/lib/$triple"
for extra in "$lib"/ogdi/*; do
    [ -d "$extra" ] && library_path="$library_path:$extra"
done
loader=$(ls "$lib"/ld-linux*.so.* 2>/dev/null | head -n 1)
if [ -z "$loader" ]; then
    echo "error: no dynamic loader in $lib (remove $base and run again)" >&2
    exit 1
fi
runner="$base/run-with-monado-libraries"
cat > "$runner" <<EOF
#!/bin/sh
exec "$loader" --library-path "$library_path" "\$@"
EOF
chmod +x "$runner"

manifest="$root/usr/share/openxr/1/openxr_monado.json"
if [ ! -f "$manifest" ]; then
    echo "error: Monado's runtime manifest $manifest is missing (remove $base and run again)" >&2
    exit 1
fi
# The manifest names the client library by its system path; point it at ours.
client=$(ls "$lib"/libopenxr_monado.so* | head -n 1)
sed "s|\"library_path\": *\"[^\"]*\"|\"library_path\": \"$client\"|" "$manifest" > "$base/openxr_monado.json"

runtime_dir=$(mktemp -d -t curved-spaces-xr.XXXXXX)
service_pid=
stop_service() {
    if [ -n "$service_pid" ] && kill -0 "$service_pid" 2>/dev/null; then
        kill -TERM "$service_pid" 2>/dev/null || true
        for _ in $(seq 50); do
            kill -0 "$service_pid" 2>/dev/null || break
            sleep 0.1
        done
        kill -KILL "$service_pid" 2>/dev/null || true
    fi
    rm -rf "$runtime_dir"
}
trap stop_service EXIT

export XDG_RUNTIME_DIR="$runtime_dir"
export XR_RUNTIME_JSON="$base/openxr_monado.json"
XRT_COMPOSITOR_NULL=1 XRT_NO_STDIN=1 SIMULATED_ENABLE=1 SIMULATED_LEFT=wmr SIMULATED_RIGHT=wmr \
    "$runner" "$root/usr/bin/monado-service" > "$base/monado-service.log" 2>&1 &
service_pid=$!
for _ in $(seq 100); do
    [ -S "$runtime_dir/monado_comp_ipc" ] && break
    if ! kill -0 "$service_pid" 2>/dev/null; then
        echo "error: monado-service stopped at start; its log:" >&2
        cat "$base/monado-service.log" >&2
        exit 1
    fi
    sleep 0.1
done
if [ ! -S "$runtime_dir/monado_comp_ipc" ]; then
    echo "error: monado-service made no socket in 10 s; its log:" >&2
    cat "$base/monado-service.log" >&2
    exit 1
fi
# Its first line names the release: "Monado(XRT) by Collabora et al '25.0.0+dfsg-2' starting up".
service_version=$(sed -n "s/.*Monado(XRT)[^']*'\([^']*\)'.*/\1/p" "$base/monado-service.log" | head -n 1)
echo "headset tests: OpenXR runtime Monado ${service_version:-(its version not logged)} from $root (pid $service_pid): null compositor, simulated headset and controllers" >&2

# The test binary runs through the same loader (Monado's client library is loaded into it).
export CARGO_TARGET_$(echo "$triple" | sed 's/-linux-gnu$/-unknown-linux-gnu/' | tr 'a-z-' 'A-Z_')_RUNNER="$runner"
export CURVED_SPACES_XR_RUNTIME="Monado ${service_version:-?} (null compositor, simulated headset)"
status=0
cargo test --features xr --test headset "$@" || status=$?
if [ "$status" -ne 0 ]; then
    echo "headset tests failed; monado-service's log is $base/monado-service.log" >&2
fi
exit "$status"
