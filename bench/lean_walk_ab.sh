#!/bin/sh
# Two builds of the library side by side (docs/benchmarks.md, "A leaner walk: what was measured"):
# bench_lean_walk of build A, then of build B, for each case in turn, ROUNDS times, so that a shared
# machine's drift falls on both alike. Prints per case each build's median frame time, the median
# of the per-round ratios B / A, and whether the two builds' images are the same bytes.
#
# Usage: sh bench/lean_walk_ab.sh A_BIN B_BIN ROUNDS SIZE FRAMES CASE...
#   e.g. sh bench/lean_walk_ab.sh ../base/build/release/bench/bench_lean_walk \
#          build/release/bench/bench_lean_walk 7 512 5 spheres64 spheres1024 terrain224 ico7
set -eu
a=$1 b=$2 rounds=$3 size=$4 frames=$5
shift 5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export MESA_GL_VERSION_OVERRIDE=2.1 MESA_GLSL_VERSION_OVERRIDE=110 MESA_SHADER_CACHE_DISABLE=true
r=0
while [ "$r" -lt "$rounds" ]; do
	for c in "$@"; do
		"$a" "$c" "$size" "$frames" 2>/dev/null >>"$tmp/$c.a"
		"$b" "$c" "$size" "$frames" 2>/dev/null >>"$tmp/$c.b"
	done
	r=$((r + 1))
done
printf '%-12s %-10s %9s %9s %7s %s\n' case plan "A ms" "B ms" "B/A" images
for c in "$@"; do
	paste -d ' ' "$tmp/$c.a" "$tmp/$c.b" | awk -v size="$size" '
		function median(v, n,   i, j, t) {
			for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
			return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
		}
		{ n++; ta[n] = $3; tb[n] = $8; q[n] = $8 / $3; plan = $2; if ($5 != $10) differ = 1; }
		END {
			printf "%-12s %-10s %9.1f %9.1f %7.3f %s\n", $1 "@" size, plan, median(ta, n), median(tb, n), median(q, n),
			       differ ? "DIFFER" : "same bytes"
		}'
done
