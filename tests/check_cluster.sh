#!/usr/bin/env bash
# make check-cluster: a single-node Slurm cluster of this machine (tests/cluster/slurm_node.sh)
# renders a shared scene as a job array of 4 tiles with the shipped script
# (examples/cluster/render_tiles.sbatch), `betelgeuse assemble` joins them, and the frame must equal
# one render of the whole scene bit for bit. The daemons are started here and stopped on any exit.
set -euo pipefail
cli=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
root=$(cd "$(dirname "$0")/.." && pwd)
scene=$root/examples/scenes/json/paper_earth_shadow.json
for tool in slurmctld slurmd munged sbatch; do
	command -v "$tool" >/dev/null || { echo "check-cluster: $tool not found (apt-get install slurm-wlm munge)" >&2; exit 1; }
done
dir=$(mktemp -d /tmp/betelgeuse-cluster.XXXXXX)
# shellcheck source=cluster/slurm_node.sh
source "$root/tests/cluster/slurm_node.sh"
cleanup() { slurm_node_stop "$dir"; rm -rf "$dir"; }
trap cleanup EXIT
echo "== check-cluster: single-node Slurm in $dir"
slurm_node_start "$dir"
sinfo
mkdir -p "$dir/tiles"
# The job sees the test's environment (GL 2.1 / GLSL 1.10 forced) and the command under test.
start=$(date +%s)
sbatch --wait --array=1-4 --cpus-per-task=1 --chdir="$dir" --export=ALL,BETELGEUSE="$cli" \
	"$root/examples/cluster/render_tiles.sbatch" "$scene" "$dir/tiles" --size 320x240
echo "job array done in $(( $(date +%s) - start )) s:"
ls -l "$dir/tiles"
"$cli" assemble "$dir"/tiles/tile_*.png -o "$dir/assembled.png"
"$cli" render "$scene" --size 320x240 -o "$dir/single.png" --quiet
if cmp "$dir/assembled.png" "$dir/single.png"; then
	echo "check-cluster: 4 Slurm tiles assembled = one render, bit for bit"
else
	echo "check-cluster: the assembled frame differs from one render" >&2
	exit 1
fi
