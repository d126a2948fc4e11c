#!/bin/sh
# Runs every cmocka suite under the test environment ($TEST_ENV), then the smoke suites again on
# EGL surfaceless and on softpipe, and closes with one "N passed, N failed" line over all of them.
# Usage: run_suites.sh "suite binaries" "smoke suite binaries"
#
# Mesa prints a two-line notice each time a context is made under MESA_GLSL_VERSION_OVERRIDE=110
# (README, "Run the tests"): it says nothing about this project, and one copy per context (over a
# hundred a run) buried the lines that do. Those two lines, and only those, are left out of what is
# shown; the counts read the suites' whole output, and the close says how many were left out.
suites=$1
smoke=$2
passed=0
failed=0
broken=""
log=$(mktemp)
trap 'rm -f "$log"' EXIT
glsl_notice='implementation error: Invalid GLSL version in shading_language_version()'
glsl_notice_next='Please report at https://gitlab.freedesktop.org/mesa/mesa/-/issues'
notices=0

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
if ! check_filter; then
	echo "run_suites.sh: the Mesa notice filter drops the wrong lines"
	broken=" notice-filter"
	failed=1
fi

run() { # label, env..., binary
	label=$1; shift
	echo "== $label"
	if env $TEST_ENV "$@" >"$log" 2>&1; then status=0; else status=$?; fi
	drop_glsl_notice <"$log"
	n=$(grep -c "^Mesa .*$glsl_notice\$" "$log")
	notices=$((notices + n))
	p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -n1)
	f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log" | tail -n1)
	passed=$((passed + ${p:-0}))
	failed=$((failed + ${f:-0}))
	if [ "$status" != 0 ] || [ -z "$p$f" ]; then
		broken="$broken $label"
		[ -z "$f" ] && failed=$((failed + 1))
	fi
}

for t in $suites; do
	run "$(basename "$t") (OSMesa, llvmpipe)" MACS_TEST_BACKEND=osmesa "$t"
done
for t in $smoke; do
	run "$(basename "$t") (EGL surfaceless, llvmpipe)" MACS_TEST_BACKEND=egl EGL_PLATFORM=surfaceless "$t"
	run "$(basename "$t") (OSMesa, softpipe)" MACS_TEST_BACKEND=osmesa GALLIUM_DRIVER=softpipe "$t"
done

echo
[ "$notices" != 0 ] && echo "($notices Mesa notices \"Invalid GLSL version\" left out: README, \"Run the tests\")"
[ -n "$broken" ] && echo "failing suites:$broken"
echo "$passed passed, $failed failed"
[ "$failed" = 0 ] && [ -z "$broken" ]
