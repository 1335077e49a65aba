#!/usr/bin/env bash
# Installs every Debian package the workbench needs (Debian 12, as root). Idempotent: quiet and
# quick when everything is there already.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev libsuitesparse-dev libgmsh-dev gmsh libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libvtk9-dev libdeal.ii-dev openmpi-bin libnlopt-cxx-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-pybind11 python3-dev python3-scipy python3-vtk9
  python3-matplotlib python3-numpy python3-pil jupyter-core jupyter-nbconvert python3-nbconvert python3-ipykernel jupyter-client
  ffmpeg
  python3-jinja2 chromium python3-meshio
  snakemake
  slurm-wlm munge  # a one-node Slurm cluster for ctest -L slurm (tests/slurm/), started by the test itself
)

missing=()
for p in "${packages[@]}"; do
  if [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" != "install ok installed" ]; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
# Packages with daemons (munge, slurmctld, slurmd) are not started by their installation: the tests
# start their own. A policy-rc.d that says no, as in Docker images, for the installation only.
policy=/usr/sbin/policy-rc.d
if [ ! -e "$policy" ]; then
  printf '#!/bin/sh\n# scripts/setup.sh: no service starts while it installs packages\nexit 101\n' | $SUDO tee "$policy" >/dev/null
  $SUDO chmod 755 "$policy"
  trap '$SUDO rm -f "$policy"' EXIT
fi
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
