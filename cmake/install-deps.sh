#!/usr/bin/env bash
# cmake/install-deps.sh — installs the Debian 12 packages nscd needs, and only those missing.
#
# Safe to run again and again: when everything is present it prints so and changes nothing
# (no apt-get update, no root needed). Otherwise it runs, non-interactively,
#   apt-get update
#   DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends <missing packages>
# as root, or through sudo when run as another user. Exits non-zero on any failure.
set -euo pipefail

# What the build, the tests and the benchmarks use (see README.md).
#   compiler and make: build-essential (a machine with g++ and make already is fine too)
#   cmake (>= 3.25), Eigen 3.4, VTK 9 (VTU/PVD output), Boost.Program_options (drivers' command
#   lines), GoogleTest, Google Benchmark, SuiteSparse and OpenMP (solvers), pkg-config, and GNU
#   parallel (the batch studies stiffness_study and accuracy_study run their plans with it).
readonly PACKAGES=(
  cmake
  libeigen3-dev
  libvtk9-dev
  libboost-program-options-dev
  libgtest-dev
  libbenchmark-dev
  libsuitesparse-dev
  libomp-dev
  pkg-config
  parallel
)

die() {
  echo "install-deps: error: $*" >&2
  exit 1
}

command -v dpkg-query >/dev/null 2>&1 ||
  die "dpkg-query not found: this script is for Debian 12 (apt/dpkg). Install the packages listed in it by hand."

# True if the package is installed ("install ok installed"), false otherwise (unknown
# packages included).
installed() {
  local status
  status="$(dpkg-query -W -f='${Status}' "$1" 2>/dev/null || true)"
  [[ "$status" == "install ok installed" ]]
}

missing=()
if ! installed build-essential && ! { installed g++ && installed make; }; then
  missing+=(build-essential)
fi
for p in "${PACKAGES[@]}"; do
  installed "$p" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all dependencies are already installed."
  exit 0
fi

echo "install-deps: installing: ${missing[*]}"

# Run as root directly, or through sudo.
as_root=()
if [[ "$(id -u)" -ne 0 ]]; then
  command -v sudo >/dev/null 2>&1 ||
    die "not root and sudo is not available; run as root: apt-get install ${missing[*]}"
  as_root=(sudo)
fi

"${as_root[@]}" apt-get update ||
  die "apt-get update failed"
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}" ||
  die "apt-get install failed for: ${missing[*]}"

# Check that every package really is there now.
still=()
for p in "${missing[@]}"; do
  installed "$p" || still+=("$p")
done
((${#still[@]} == 0)) || die "still missing after apt-get install: ${still[*]}"
echo "install-deps: done."
