#!/bin/sh
# What mesh filters cost (docs/gpu_pipeline.md, "Filters: sides and cut-outs"): the bunny scene
# rendered by the command on the GPU with its bunny solid, front-only, and cut out by a textured
# coverage on every triangle, in interleaved rounds; prints each variant's median wall time and its
# ratio to the solid one's. Whole-process times (the program's compile included, the same for each).
#
# Usage: sh bench/mesh_filters.sh [BETELGEUSE] [ROUNDS] [SIZE]   (default build/release/betelgeuse 5 1920x1440)
set -eu
bin=${1:-build/release/betelgeuse}
rounds=${2:-5}
size=${3:-1920x1440}
top=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The three scenes from the shipped one: the bunny's material "clay" with sides or a cut-out added,
# and the mesh path made absolute.
python3 - "$top" "$tmp" <<'EOF'
import json, os, sys
sys.path.insert(0, os.path.join(sys.argv[1], "tests", "data"))
from make_image_models import png
top, tmp = sys.argv[1], sys.argv[2]
scene = json.load(open(os.path.join(top, "examples", "scenes", "json", "bunny.json")))
scene["objects"][0]["mesh"]["file"] = os.path.join(top, "tests", "data", "bunny.ply")
with open(os.path.join(tmp, "hole.png"), "wb") as f:
    f.write(png([[(255, 255, 255, 0 if 1 <= x <= 2 and 1 <= y <= 2 else 255) for x in range(4)] for y in range(4)]))
variants = {"solid": {}, "front": {"sides": "front"},
            "cut": {"coverage": {"texture": "hole"}, "coverage_cutoff": 0.5}}
for name, extra in variants.items():
    s = json.loads(json.dumps(scene))
    s["materials"]["clay"].update(extra)
    if name == "cut":
        s["textures"] = {"hole": {"file": "hole.png", "encoding": "linear"}}
    json.dump(s, open(os.path.join(tmp, name + ".json"), "w"))
EOF

export MESA_GL_VERSION_OVERRIDE=2.1 MESA_GLSL_VERSION_OVERRIDE=110
run() { # variant: prints the wall seconds of one render
	start=$(date +%s.%N)
	"$bin" render "$tmp/$1.json" -o "$tmp/$1.png" --size "$size" --renderer gpu -q
	end=$(date +%s.%N)
	echo "$start $end" | awk '{printf "%.3f\n", $2 - $1}'
}
for v in solid front cut; do run $v >/dev/null; done # warm-up: shader caches, file caches
for r in $(seq "$rounds"); do
	for v in solid front cut; do run $v >>"$tmp/$v.times"; done
done
median() { sort -n "$1" | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
base=$(median "$tmp/solid.times")
printf 'bunny at %s, %s interleaved rounds, median wall seconds and ratio to solid\n' "$size" "$rounds"
for v in solid front cut; do
	m=$(median "$tmp/$v.times")
	printf '%-6s %7.3f  %5.2f\n' "$v" "$m" "$(echo "$m $base" | awk '{print $1 / $2}')"
done
