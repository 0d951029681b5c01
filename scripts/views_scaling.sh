#!/usr/bin/env bash
# Many views against thread count: lanecast --views and the Embree 3 caster --views on the same
# orbit of the armadillo subdivided 3 times (3,328,000 triangles), 1920x1080, at THREADS
# (default 1 2 4 8 16), VIEWS views (default 20). Prints one line per program and thread count:
# lanecast's load, median per-view setup + render (from --stats), output time and whole wall
# time; Embree's build, median view and total. Writes into $OUT (default target/views-scaling).
#
# Environment (paths relative to the repository root or absolute):
#   LANECAST    the lanecast binary (default target/release/lanecast, `cargo build --release`)
#   EMBREE      the Embree caster (default target/embree/embree_cast, built by
#               scripts/vs_embree.py)
#   EMBREE_LIB  a directory holding libembree3.so.3, put first on LD_LIBRARY_PATH (default
#               target/embree/lib, used only if it exists; otherwise the system's Embree 3, e.g.
#               Debian's libembree-dev). A libembree3.so.3.xz there is unpacked beside it first.
#   ORBIT       the orbit generator (default ../shared/anchors/orbit_views.py)
#   SCAN        (optional) an armadillo_3.obj already written by scripts/subdivide.py, to skip
#               writing one
# and python3. Example, with both programs built elsewhere:
#   LANECAST=/opt/lc/lanecast EMBREE=/opt/lc/embree_cast EMBREE_LIB=/opt/lc/lib \
#     bash scripts/views_scaling.sh
set -u
cd "$(dirname "$0")/.."
LANECAST=${LANECAST:-target/release/lanecast}
EMBREE=${EMBREE:-target/embree/embree_cast}
EMBREE_LIB=${EMBREE_LIB:-target/embree/lib}
ORBIT=${ORBIT:-../shared/anchors/orbit_views.py}
OUT=${OUT:-target/views-scaling}
for f in "$LANECAST" "$EMBREE" "$ORBIT"; do
  [ -e "$f" ] || { echo "views_scaling.sh: $f is missing (see the comment at the top)" >&2; exit 1; }
done
if [ -d "$EMBREE_LIB" ]; then
  if [ -f "$EMBREE_LIB/libembree3.so.3.xz" ] && [ ! -e "$EMBREE_LIB/libembree3.so.3" ]; then
    xz -dk "$EMBREE_LIB/libembree3.so.3.xz"
  fi
  export LD_LIBRARY_PATH=$(realpath "$EMBREE_LIB")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
fi
mkdir -p "$OUT"
R=$OUT/results.txt
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2) / $(nproc) cpus" > "$R"
if [ -n "${SCAN:-}" ]; then
  ln -s "$(realpath "$SCAN")" "$work/armadillo_3.obj"
else
  python3 scripts/subdivide.py scenes/meshes/armadillo.obj "$work/armadillo_3.obj" 3 >> "$R" 2>&1
fi
printf 'camera eye 60 60 -330 look 0 22 0 up 0 1 0 fov 40\nmesh armadillo_3.obj\n' > "$work/armadillo_3.sc"
python3 "$ORBIT" "$work/armadillo_3.sc" "${VIEWS:-20}" > "$work/views.txt"
mkdir -p "$work/frames"
for t in ${THREADS:-1 2 4 8 16}; do
  rm -f "$work"/frames/*
  s=$(date +%s.%N)
  "$LANECAST" -i "$work/armadillo_3.sc" --views "$work/views.txt" -size 1920x1080 \
      -o "$work/frames/v%04d.bmp" --stats "$work/s$t.json" --threads "$t" 2>>"$R"
  e=$(date +%s.%N)
  python3 - "$t" "$s" "$e" "$work/s$t.json" >> "$R" <<'PY'
import json, statistics, sys
t, s, e, f = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
j = json.load(open(f)); each = j["views"]["each"]
med = lambda k: statistics.median(v[k] for v in each) * 1e3
print(f"lanecast threads={t} load_ms={j['phases_s']['load']*1e3:.1f} "
      f"view_median_ms={med('setup_s')+med('render_s'):.1f} setup_ms={med('setup_s'):.1f} "
      f"render_ms={med('render_s'):.1f} output_ms={med('output_s'):.1f} whole_s={e-s:.2f} "
      f"peak_rss_mb={j['peak_rss_bytes']/2**20:.0f}")
PY
  echo "embree threads=$t $("$EMBREE" "$work/armadillo_3.sc" --size 1920x1080 --api 8 --threads "$t" \
      --views "$work/views.txt" | grep -E 'build_ms|views_total_ms|view_median_ms' | tr '\n' ' ')" >> "$R"
done
cat "$R"
