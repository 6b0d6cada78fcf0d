#!/usr/bin/env bash
# Install what is missing, build grainmpm (Release) and run a shipped case:
#   bash scripts/run-case.sh [prm/two_disks_explicit.prm]
# Output goes to the directory named in the case (results-<case>/).
set -euo pipefail
cd "$(dirname "$0")/.."

case_file="${1:-prm/two_disks_explicit.prm}"
bash scripts/install-dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2 --target grainmpm
./build/source/grainmpm "$case_file"
