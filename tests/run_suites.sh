#!/bin/sh
# Runs every cmocka suite under the test environment ($TEST_ENV), then the smoke suites again on
# EGL surfaceless and on softpipe, and closes with one "N passed, N failed" line over all of them.
# Usage: run_suites.sh "suite binaries" "smoke suite binaries"
suites=$1
smoke=$2
passed=0
failed=0
broken=""
log=$(mktemp)
trap 'rm -f "$log"' EXIT

run() { # label, env..., binary
	label=$1; shift
	echo "== $label"
	if env $TEST_ENV "$@" >"$log" 2>&1; then status=0; else status=$?; fi
	cat "$log"
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
[ -n "$broken" ] && echo "failing suites:$broken"
echo "$passed passed, $failed failed"
[ "$failed" = 0 ] && [ -z "$broken" ]
