#!/usr/bin/env bash
# Installs the Debian 12 packages baker builds and tests with, only those that are missing, then
# the npm packages the engine-format tests use (package-lock.json, with npm ci) when they are
# missing or older than the lock file. As root it calls apt-get directly, otherwise through sudo.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libembree-dev libtinygltf-dev libopenimageio-dev libopenexr-dev libopenvdb-dev libboost-iostreams-dev
  libtbb-dev libeigen3-dev libcli11-dev nlohmann-json3-dev libfmt-dev libgtest-dev libopenmpi-dev openmpi-bin
  libopenvdb-tools openexr openimageio-tools glslang-tools
  chromium
)
# Node and npm from Debian, unless a node and an npm are already on the PATH.
command -v node > /dev/null && command -v npm > /dev/null || packages+=(nodejs npm)
# --sanitizers: clang's sanitizer runtimes and libFuzzer, for scripts/test-sanitized.sh and fuzz.sh.
if [ "${1:-}" = "--sanitizers" ]; then packages+=(clang libclang-rt-14-dev); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cd "$(dirname "$0")/.."
if [ ! node_modules/.package-lock.json -nt package-lock.json ]; then
  echo "installing npm packages (npm ci)" >&2
  npm ci --no-audit --no-fund --loglevel=error
fi
