#!/usr/bin/env bash
# Installs softdrop's build and test dependencies from Debian 12 packages.
# Non-interactive and safe to run twice; needs root (or sudo).
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build ccache pkg-config clang libclang-rt-dev clang-format clang-tidy
  libeigen3-dev libsuitesparse-dev libopenblas0-pthread libnlopt-cxx-dev libnlopt-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libsqlite3-dev sqlite3 libsqlitecpp-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libpagmo-dev libcli11-dev nlohmann-json3-dev libtomlplusplus-dev libcairo2-dev libpng-dev libtiff-dev libgif-dev fonts-dejavu-core libtinyxml2-dev ffmpeg libtbb-dev
  pybind11-dev python3-dev python3-numpy python3-pandas python3-pytest python3-matplotlib python3-tqdm python3-nbclient python3-ipykernel python3-mypy
  python3-venv python3-pip python3-setuptools python3-wheel
  libopenmpi-dev openmpi-bin
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""; [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
