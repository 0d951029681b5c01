#!/usr/bin/env bash
# Two lanecast builds, A and B, alternated on the many-views run of scripts/views_scaling.sh (the
# armadillo subdivided 3 times, 1920x1080, a VIEWS-view orbit, default 10) at THREADS (default
# "16 2", each twice); prints each run's median per-view setup and render from --stats.
#
# Usage: bash scripts/views_ab.sh [A [B]], or A=... B=... bash scripts/views_ab.sh
#   A      the first lanecast binary (required, as the first argument or in the environment)
#   B      the second (default target/release/lanecast)
#   ORBIT  the orbit generator (default ../shared/anchors/orbit_views.py)
# Paths are relative to the repository root or absolute; needs python3. Example, a build kept
# from before a change against the current one:
#   cp target/release/lanecast target/lanecast_before   # then change, cargo build --release
#   bash scripts/views_ab.sh target/lanecast_before target/release/lanecast
set -u
cd "$(dirname "$0")/.."
A=${1:-${A:-}}
B=${2:-${B:-target/release/lanecast}}
ORBIT=${ORBIT:-../shared/anchors/orbit_views.py}
for f in "${A:?A=first lanecast binary (first argument)}" "$B" "$ORBIT"; do
  [ -e "$f" ] || { echo "views_ab.sh: $f is missing" >&2; exit 1; }
done
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
python3 scripts/subdivide.py scenes/meshes/armadillo.obj "$work/a3.obj" 3 >&2
printf 'camera eye 60 60 -330 look 0 22 0 up 0 1 0 fov 40\nmesh a3.obj\n' > "$work/a3.sc"
python3 "$ORBIT" "$work/a3.sc" "${VIEWS:-10}" > "$work/v.txt"
mkdir -p "$work/frames"
for round in 1 2; do
  for t in ${THREADS:-16 2}; do
    for b in "$A" "$B"; do
      rm -f "$work"/frames/*
      "$b" -i "$work/a3.sc" --views "$work/v.txt" -size 1920x1080 -o "$work/frames/v%04d.bmp" \
          --stats "$work/s.json" --threads "$t"
      python3 - "$b" "$t" "$work/s.json" <<'PY'
import json, statistics, sys
b, t, f = sys.argv[1:]
each = json.load(open(f))["views"]["each"]
m = lambda k: statistics.median(v[k] for v in each) * 1e3
print(f"{b} threads={t} setup_ms={m('setup_s'):.1f} render_ms={m('render_s'):.1f} "
      f"view_ms={m('setup_s') + m('render_s'):.1f}")
PY
    done
  done
done
