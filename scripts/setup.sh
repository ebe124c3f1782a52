#!/usr/bin/env bash
# Installs the Debian packages terracal builds against. Idempotent: when everything is
# present it only checks (a second or so); otherwise one apt-get update + install.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libceres-dev libnlopt-dev libnlopt-cxx-dev libgsl-dev libhdf5-dev
  catch2 nlohmann-json3-dev libcli11-dev libfmt-dev libspdlog-dev
  libsundials-dev libsqlite3-dev libopenmpi-dev openmpi-bin
  gnuplot-nox
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=""
if [ "$(id -u)" -ne 0 ]; then sudo_cmd="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo_cmd apt-get update -qq
$sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "setup: done"
