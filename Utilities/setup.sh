#!/usr/bin/env bash
# Shared set-up of the README's two commands: installs the Debian 12 packages
# that are missing, then configures (once) and builds incrementally into
# build/. Sourced by Utilities/run.sh and Utilities/test.sh.
set -euo pipefail

THINTISSUE_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
THINTISSUE_BUILD="${THINTISSUE_BUILD:-$THINTISSUE_ROOT/build}"

THINTISSUE_PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config git
  libvtk9-dev libvtk9-qt-dev python3-vtk9 python3 mpi-default-dev
  libeigen3-dev libsuitesparse-dev libopenblas0-pthread libcgal-dev qtbase5-dev libassimp-dev
  libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libtbb-dev
  xvfb xauth
)

thintissue_install_packages() {
  local missing=()
  local package
  for package in "${THINTISSUE_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
  if [ "${#missing[@]}" -eq 0 ]; then
    return 0
  fi
  echo "ThinTissue: installing missing Debian packages: ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo=(sudo)
    else
      echo "ThinTissue: need root or sudo to install: ${missing[*]}" >&2
      exit 1
    fi
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
}

thintissue_build() {
  if [ ! -f "$THINTISSUE_BUILD/build.ninja" ]; then
    cmake -S "$THINTISSUE_ROOT" -B "$THINTISSUE_BUILD" -G Ninja \
      -DCMAKE_BUILD_TYPE="${THINTISSUE_BUILD_TYPE:-Release}" \
      ${THINTISSUE_CMAKE_ARGS:-}
  fi
  # Ninja re-runs CMake by itself when a CMakeLists.txt changed.
  cmake --build "$THINTISSUE_BUILD" -- -j"$(nproc)"
}

thintissue_install_packages
thintissue_build
