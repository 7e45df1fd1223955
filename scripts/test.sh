#!/usr/bin/env bash
# Installs what is missing, builds Release in build/ and runs the whole test suite.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/setup.sh"
cd "$here/build"
jobs=$(nproc)
ctest --output-on-failure -j "$jobs" --timeout 900 "$@"
