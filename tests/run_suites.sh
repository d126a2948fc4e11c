#!/bin/sh
# Runs every cmocka suite under the test environment ($TEST_ENV), then the smoke suites again on
# the other backend and on softpipe, several suites at a time, and closes with one
# "N passed, N failed, N skipped" line over all of them.
# Usage: run_suites.sh "suite binaries" "smoke suite binaries"
# Environment: TEST_ENV (the Mesa settings of every run), PROBE (the backend probe program),
# CHECK_JOBS (suites run at once; default: the number of processors), TIMES (a file that keeps each
# run's duration, so that the next run starts the longest first; default: none), SUITE_BACKEND
# (device: every suite on the first EGL device, a GPU, and no smoke reruns; surfaceless: every suite
# on EGL surfaceless and no smoke reruns, SUITE_DRIVER naming the driver TEST_ENV picks), RUN_WITH (a command
# that runs each suite, such as valgrind with its options; default: none), SHADER_CACHE (no: every
# run without Mesa's shader cache, as under valgrind, where Mesa's own cache writes raise reports).
#
# Where OSMesa is installed (Mesa 25.0 and older) every suite runs on it and the smoke suites also
# on EGL surfaceless; where it is not (Mesa 25.1 and later) every suite runs on EGL surfaceless, and
# the OSMesa runs are reported as skipped, with as many tests as the suite holds.
#
# The suites are compile-bound (llvmpipe spends most of a suite in LLVM, one thread per shader), so
# suites run side by side: on 2 cores two of them take the time of one. Each run gets a shader cache
# of its own, empty at the start and removed at the end: a suite recompiles the same programs in
# many tests, and the cache spares that within the one process, under the one set of Mesa settings
# that made each entry. No compile result crosses processes, runs or settings, the way a shader that
# failed under one GLSL version could once be reported compiled from a cache filled under another.
#
# Mesa prints a two-line notice each time a context is made under MESA_GLSL_VERSION_OVERRIDE=110
# (README, "Run the tests"): it says nothing about this project, and one copy per context (over a
# hundred a run) buried the lines that do. Those two lines, and only those, are left out of what is
# shown; the counts read the suites' whole output, and the close says how many were left out.
# One run of the list: "id|label|binary|settings...". Runs it with its own shader cache and leaves
# its output in $work/id.log, its exit status in $work/id.status, its seconds in $work/id.time.
if [ "$1" = "--one" ]; then
	IFS='|' read -r id label binary settings <<EOF
$2
EOF
	cache="$work_dir/$id.cache"
	start=$(date +%s.%N)
	cache_env="MESA_SHADER_CACHE_DISABLE=false MESA_SHADER_CACHE_DIR=$cache"
	[ "$SHADER_CACHE" = no ] && cache_env="MESA_SHADER_CACHE_DISABLE=true"
	# shellcheck disable=SC2086 # TEST_ENV, cache_env and settings are lists of NAME=value words
	if env $TEST_ENV $cache_env $settings $RUN_WITH "$binary" \
		>"$work_dir/$id.log" 2>&1; then status=0; else status=$?; fi
	end=$(date +%s.%N)
	rm -rf "$cache"
	echo "$status" >"$work_dir/$id.status"
	awk -v s="$start" -v e="$end" 'BEGIN { printf "%.1f\n", e - s }' >"$work_dir/$id.time"
	echo "   done: $label ($(cat "$work_dir/$id.time") s)"
	exit 0
fi

suites=$1
smoke=$2
jobs=${CHECK_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
glsl_notice='implementation error: Invalid GLSL version in shading_language_version()'
glsl_notice_next='Please report at https://gitlab.freedesktop.org/mesa/mesa/-/issues'

# Copies stdin to stdout without Mesa's GLSL-version notice: a line ending in $glsl_notice, and
# the report line right after it (a report line after anything else is kept).
drop_glsl_notice() {
	awk -v notice="$glsl_notice" -v next_line="$glsl_notice_next" '
		after_notice && $0 == next_line { after_notice = 0; next }
		{ after_notice = 0 }
		/^Mesa / && substr($0, length($0) - length(notice) + 1) == notice { after_notice = 1; next }
		{ print }'
}

# The filter on a sample: the notice goes, everything else (another Mesa error, a report line of
# its own, cmocka's lines) stays. A broken filter fails the run rather than hide a line.
check_filter() {
	sample="[ RUN      ] a
Mesa 22.3.6 implementation error: Invalid GLSL version in shading_language_version()
$glsl_notice_next
Mesa 22.3.6 implementation error: something else
$glsl_notice_next
$glsl_notice_next
[       OK ] a"
	kept="[ RUN      ] a
Mesa 22.3.6 implementation error: something else
$glsl_notice_next
$glsl_notice_next
[       OK ] a"
	[ "$(printf '%s\n' "$sample" | drop_glsl_notice)" = "$kept" ]
}

passed=0
failed=0
skipped=0
broken=""
notices=0
if ! check_filter; then
	echo "run_suites.sh: the Mesa notice filter drops the wrong lines"
	broken=" notice-filter"
	failed=1
fi

# Where OSMesa can be had, it stays the main backend, as on the machines the tests were measured
# on; elsewhere EGL surfaceless takes every run.
if [ "$SUITE_BACKEND" = device ]; then
	main="MACS_TEST_BACKEND=device"; main_name="EGL device"; main_driver="the device's driver"
	other=""; soft=""; osmesa=device
elif [ "$SUITE_BACKEND" = surfaceless ]; then
	# Every suite on EGL surfaceless with the driver TEST_ENV picks (make check-zink: zink), no reruns.
	main="MACS_TEST_BACKEND=egl EGL_PLATFORM=surfaceless"; main_name="EGL surfaceless"
	main_driver="${SUITE_DRIVER:-llvmpipe}"
	other=""; soft=""; osmesa=unused
elif [ -n "$PROBE" ] && osmesa_why=$("$PROBE" osmesa 2>&1); then
	main="MACS_TEST_BACKEND=osmesa"; main_name="OSMesa"
	other="MACS_TEST_BACKEND=egl EGL_PLATFORM=surfaceless"; other_name="EGL surfaceless"
	soft="MACS_TEST_BACKEND=osmesa GALLIUM_DRIVER=softpipe"; soft_name="OSMesa"
	osmesa=yes
else
	echo "OSMesa is not available, every suite runs on EGL surfaceless: ${osmesa_why:-no probe}"
	main="MACS_TEST_BACKEND=egl EGL_PLATFORM=surfaceless"; main_name="EGL surfaceless"
	other=""
	soft="MACS_TEST_BACKEND=egl EGL_PLATFORM=surfaceless GALLIUM_DRIVER=softpipe"; soft_name="EGL surfaceless"
	osmesa=no
fi

n=0
add() { # label, binary, settings
	n=$((n + 1))
	echo "$n|$1|$2|$3" >>"$work/list"
}
: >"$work/list"
for t in $suites; do
	add "$(basename "$t") ($main_name, ${main_driver:-llvmpipe})" "$t" "$main"
done
for t in $smoke; do
	[ -n "$other" ] && add "$(basename "$t") ($other_name, llvmpipe)" "$t" "$other"
	[ -n "$soft" ] && add "$(basename "$t") ($soft_name, softpipe)" "$t" "$soft"
done

# Longest first, by the last run's times where TIMES keeps them, so that no long suite starts last.
if [ -n "$TIMES" ] && [ -f "$TIMES" ]; then
	awk -F'|' 'NR == FNR { t[$1] = $2; next } { print (($2 in t) ? t[$2] : 0) "|" $0 }' "$TIMES" "$work/list" |
		sort -t'|' -k1,1 -g -r | cut -d'|' -f2- >"$work/order"
else
	cp "$work/list" "$work/order"
fi

echo "== $n suite runs, $jobs at a time"
tr '\n' '\0' <"$work/order" | work_dir="$work" TEST_ENV="$TEST_ENV" RUN_WITH="$RUN_WITH" SHADER_CACHE="$SHADER_CACHE" \
	xargs -0 -P "$jobs" -n 1 sh "$0" --one

# The logs in the list's order, then the counts.
: >"$work/times"
while IFS='|' read -r id label binary settings; do
	log="$work/$id.log"
	status=$(cat "$work/$id.status" 2>/dev/null || echo "not run")
	echo "== $label ($(cat "$work/$id.time" 2>/dev/null) s)"
	drop_glsl_notice <"$log"
	echo "$label|$(cat "$work/$id.time" 2>/dev/null)" >>"$work/times"
	k=$(grep -c "^Mesa .*$glsl_notice\$" "$log")
	notices=$((notices + k))
	p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -n1)
	f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -n1)
	s=$(sed -n 's/^\[  SKIPPED \] \([0-9]*\) test.*/\1/p' "$log" | tail -n1)
	passed=$((passed + ${p:-0}))
	failed=$((failed + ${f:-0}))
	skipped=$((skipped + ${s:-0}))
	if [ "$status" != 0 ] || [ -z "$p$f" ]; then
		broken="$broken $label"
		[ -z "$f" ] && failed=$((failed + 1))
	fi
done <"$work/list"
[ -n "$TIMES" ] && cp "$work/times" "$TIMES"

# Without OSMesa its smoke runs cannot happen: each counts its suite's tests as skipped.
if [ "$osmesa" = no ]; then
	for t in $smoke; do
		id=$(awk -F'|' -v b="$t" '$3 == b { print $1; exit }' "$work/list")
		k=$(sed -n 's/^\[==========\] \([0-9]*\) test(s) run.*/\1/p' "$work/$id.log" | tail -n1)
		echo "== $(basename "$t") (OSMesa, llvmpipe and softpipe): skipped, OSMesa is not installed (${k:-0} tests each)"
		skipped=$((skipped + 2 * ${k:-0}))
	done
fi

echo
[ "$notices" != 0 ] && echo "($notices Mesa notices \"Invalid GLSL version\" left out: README, \"Run the tests\")"
[ -n "$broken" ] && echo "failing suites:$broken"
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" = 0 ] && [ -z "$broken" ]
