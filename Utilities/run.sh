#!/usr/bin/env bash
# README command 1: set up, build, and run the main job. Arguments go to the
# program (e.g. a mesh file). Without a display it renders offscreen under
# Xvfb and writes build/thintissue-demo.png and its timings.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$THINTISSUE_BUILD"
if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1280x1024x24" "$THINTISSUE_BUILD/bin/ThinTissueDemo" \
    --offscreen --screenshot "$THINTISSUE_BUILD/thintissue-demo.png" "$@"
fi
exec "$THINTISSUE_BUILD/bin/ThinTissueDemo" "$@"
