#!/usr/bin/env bash
# README command 1: set up, build, and run the main job. Arguments go to the
# program (e.g. a mesh file). Without a display it renders offscreen under
# Xvfb and writes build/thintissue-demo.png and its timings.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$THINTISSUE_BUILD"
# Without a display the demo re-runs itself under xvfb-run, offscreen.
if [ -z "${DISPLAY:-}" ]; then
  exec "$THINTISSUE_BUILD/bin/ThinTissueDemo" --screenshot "$THINTISSUE_BUILD/thintissue-demo.png" "$@"
fi
exec "$THINTISSUE_BUILD/bin/ThinTissueDemo" "$@"
