#!/usr/bin/env bash
# Installs the Debian 12 packages baker builds with, only those that are missing.
# As root it calls apt-get directly, otherwise through sudo.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libembree-dev libtinygltf-dev libopenimageio-dev libopenexr-dev libopenvdb-dev libboost-iostreams-dev
  libtbb-dev libeigen3-dev libcli11-dev nlohmann-json3-dev libfmt-dev libgtest-dev
  libopenvdb-tools openexr openimageio-tools glslang-tools
)
# --sanitizers: clang's sanitizer runtimes and libFuzzer, for scripts/test-sanitized.sh and fuzz.sh.
if [ "${1:-}" = "--sanitizers" ]; then packages+=(clang libclang-rt-14-dev); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "installing: ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
