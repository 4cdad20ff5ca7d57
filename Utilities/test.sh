#!/usr/bin/env bash
# README command 2: set up, build, and run the whole test suite; rendering
# tests run inside a virtual X server. Extra arguments go to ctest.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$THINTISSUE_BUILD"
exec xvfb-run -a -s "-screen 0 1280x1024x24" \
  ctest --output-on-failure -j"$(nproc)" "$@"
