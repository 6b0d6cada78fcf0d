#!/usr/bin/env bash
# Install everything grainmpm needs from Debian 12 (bookworm) packages.
# Idempotent: packages already present are skipped; safe to run repeatedly.
# Must run as root (or through sudo) on a fresh machine.
set -euo pipefail

packages=(
  libdeal.ii-dev   # deal.II 9.4.1 with Trilinos, p4est, PETSc, Open MPI, Boost, TBB
  libsuitesparse-dev  # CHOLMOD: Linear solver/Preconditioner = sparse Cholesky
  libopenblas0-serial # optimised BLAS: the Cholesky factorisation 2 times faster than with the reference BLAS
  cmake
  make
  g++
  ccache
  numdiff
  clang-format-16
  paraview           # ParaView 5.11: pvbatch for visualization/*.py
  python3-paraview
  xvfb               # xvfb-run: a virtual display for headless rendering
  xauth
  python3-matplotlib # visualization/plot_energy.py
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi

echo "install-dependencies: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
