#!/usr/bin/env bash
# README command 1: set up, build, and run the main job: the training
# simulator on the meniscus examination. Arguments go to the simulator.
# Without a display it replays offscreen under Xvfb and writes the pictures,
# metrics.json and timings.json into build/simulator/.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$THINTISSUE_BUILD"
if [ -z "${DISPLAY:-}" ]; then
  exec "$THINTISSUE_BUILD/bin/ThinTissueSimulator" --snapshots 1.0,2.5,2.65 \
    --output "$THINTISSUE_BUILD/simulator" "$@"
fi
exec "$THINTISSUE_BUILD/bin/ThinTissueSimulator" "$@"
