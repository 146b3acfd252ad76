#!/usr/bin/env bash
# Installs every Debian package mpgc builds, tests and runs with, by name (Debian 12 bookworm), and
# the npm packages the tests read recordings and the live view with, at the versions pinned in the repo
# (tests/recorder/js/package-lock.json, `npm ci`).
# Usage: deploy/install-deps.sh [--check]   (--check: list what is missing, install nothing)
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config python3 git
  # middleware and libraries (CMakeLists.txt find_package)
  cyclonedds-dev cyclonedds-tools
  libeigen3-dev libfcl-dev libspdlog-dev libyaml-cpp-dev libcli11-dev libnanoflann-dev nlohmann-json3-dev
  libgeographiclib-dev libgdal-dev libompl-dev
  # recordings: zstd-compressed MCAP chunks; the live view's server: Boost.Beast, header-only (components/recorder)
  libzstd-dev libboost-dev
  # tests and benchmarks; clang and libFuzzer for the long fuzz runs (tests/fuzz/README.md)
  libgtest-dev libgmock-dev clang libfuzzer-14-dev
  # multi-host tests: network namespaces, loss and delay (iptables + an NFQUEUE delayer: this kernel
  # has no netem), packet captures; containers (podman on runc, a base image made with debootstrap);
  # DDS Security (openssl makes and signs the certificates and documents)
  iproute2 iptables libnetfilter-queue-dev tcpdump podman runc debootstrap openssl
  # hardware in the loop: gpsd and libgps for the ship bridge, gpsfake (gpsd-clients) for the log replays
  gpsd gpsd-clients libgps-dev
  # recordings and the live view read back with other people's code (tests/recorder/js: @mcap/core,
  # Foxglove's omgidl reader and WebSocket client; the web page in headless chromium via playwright-core)
  nodejs chromium
)
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
NPM_DIR="$ROOT/tests/recorder/js"

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm: Debian's package of that name, unless the installed nodejs brings its own.
command -v npm >/dev/null 2>&1 || missing+=(npm)
# The pinned npm packages are stale when node_modules is missing or older than the lock file.
npm_stale() { [ ! -f "$NPM_DIR/node_modules/.package-lock.json" ] || [ "$NPM_DIR/package-lock.json" -nt "$NPM_DIR/node_modules/.package-lock.json" ]; }
npm_install() {
  echo "install-deps: npm ci in ${NPM_DIR#"$ROOT"/}"
  # playwright-core drives Debian's chromium: never let anything download a browser of its own.
  (cd "$NPM_DIR" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)
}

if [ "${1:-}" = "--check" ]; then
  if [ ${#missing[@]} -gt 0 ]; then printf '%s\n' "${missing[@]}"; fi
  if npm_stale; then echo "npm:${NPM_DIR#"$ROOT"/}"; fi
  exit 0
fi
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  if npm_stale; then npm_install; fi
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}" >&2
  echo "run as root:  apt-get update && apt-get install -y ${missing[*]}" >&2
  exit 1
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
if npm_stale; then npm_install; fi
