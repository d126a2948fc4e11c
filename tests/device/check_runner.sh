#!/bin/sh
# Holds tests/run_suites.sh to its handling of crashes and timeouts (make check-runner; the device
# check runs it first, with that machine's debugger):
# - tests/device/crash_suite: one test fails, one skips, one dies of SIGSEGV (cmocka catches it),
#   one of SIGABRT (the process ends); the tests after the first crash run again, each alone, so the
#   counts are 2 passed, 3 failed, 1 skipped, the failures named; where a debugger is given
#   (BACKTRACE, else gdb or cuda-gdb where installed), each crashed test's backtrace names its function;
# - a stand-in suite that hangs in its second test of three under SUITE_TIMEOUT=2: 1 passed,
#   1 failed, the third named as not run, and the kept log holds the lines written before the stop.
# Usage: check_runner.sh CRASH_SUITE [LOG_FOLDER]
here=$(dirname "$0")
crash_suite=$1
out=${2:-$(dirname "$crash_suite")/runner-check}
rm -rf "$out"
mkdir -p "$out" || exit 1
if [ -z "$BACKTRACE" ]; then
	for d in gdb cuda-gdb; do
		command -v $d >/dev/null 2>&1 && BACKTRACE="$d -batch -ex run -ex bt --args" && break
	done
fi
status=0
fail() {
	echo "check-runner: $*"
	status=1
}

# SUITE_BACKEND=device only picks the labels here: neither program makes a GL context.
SUITE_BACKEND=device SUITE_PRINT=failures SUITE_LOGS="$out/crash" BACKTRACE="$BACKTRACE" \
	sh "$here/../run_suites.sh" "$crash_suite" "" >"$out/crash.out" 2>&1
log=$(ls "$out"/crash/*crash_suite*.log 2>/dev/null | head -n1)
[ "$(tail -n1 "$out/crash.out")" = "2 passed, 3 failed, 1 skipped" ] ||
	fail "crash_suite: expected \"2 passed, 3 failed, 1 skipped\", got \"$(tail -n1 "$out/crash.out")\""
grep -q -- "-- failing in crash_suite.*: fails_by_assertion dies_of_sigsegv dies_of_sigabrt$" "$out/crash.out" ||
	fail "crash_suite: the failing tests are not named"
grep -q "passes_after again, alone in a fresh process" "$log" 2>/dev/null ||
	fail "crash_suite: the tests after the crash did not run again"
if [ -n "$BACKTRACE" ]; then
	for f in raise_segv dies_of_sigabrt; do
		grep -q "#[0-9].* $f (" "$log" 2>/dev/null || fail "crash_suite: no backtrace through $f ($BACKTRACE)"
	done
else
	echo "check-runner: no gdb or cuda-gdb here: the backtraces are not checked"
fi

# The stand-in: cmocka's lines for one test that passes and one that never ends, and the list of
# its three tests that tests/util_suite.c would give.
mkdir -p "$out/stand-in"
hang="$out/stand-in/hang_suite"
printf '%s\n' '#!/bin/sh' \
	'[ "$BG_TEST_LIST" = 1 ] && { printf "bg-test: %s\n" quick hangs never_reached; exit 0; }' \
	'echo "[==========] Running 3 test(s)."' 'echo "[ RUN      ] quick"' \
	'echo "[       OK ] quick"' 'echo "[ RUN      ] hangs"' 'exec sleep 60' >"$hang"
chmod +x "$hang"
SUITE_BACKEND=device SUITE_TIMEOUT=2 SUITE_LOGS="$out/hang" sh "$here/../run_suites.sh" "$hang" "" >"$out/hang.out" 2>&1
[ "$(tail -n1 "$out/hang.out")" = "1 passed, 1 failed, 0 skipped" ] ||
	fail "hang_suite: expected \"1 passed, 1 failed, 0 skipped\", got \"$(tail -n1 "$out/hang.out")\""
grep -q "timed out after 2 s in hangs; 1 tests after it did not run" "$out/hang.out" ||
	fail "hang_suite: the timeout is not reported with the test it stopped and the one it kept from running"
grep -q "^ *[0-9.]* \[ RUN      \] hangs$" "$out"/hang/*.log 2>/dev/null || fail "hang_suite: the kept log lost its lines"

[ $status = 0 ] && echo "check-runner: crashes and timeouts handled (logs in $out)"
exit $status
