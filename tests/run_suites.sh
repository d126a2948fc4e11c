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
# run without Mesa's shader cache, as under valgrind, where Mesa's own cache writes raise reports),
# SUITE_TIMEOUT (seconds a suite run may take before it is stopped and counted failed, "timed out
# after N s"; default: none), SUITE_LOGS (the folder that keeps the logs; default
# build/suite-logs/<date>-<time>-<pid>, the last 10 of them kept), SUITE_PRINT (failures: print the
# logs of failing runs only; default: every log), BACKTRACE (a debugger command line that runs a
# program and prints its stack, such as "gdb -batch -ex run -ex bt --args": each test that crashed
# runs once more under it), PROFILES and PROFILE_SUITES (each suite of PROFILE_SUITES runs once more
# on the main backend under each MACS limit profile of PROFILES, MACS_TEST_PROFILE set: the GPU
# scene suites as a legacy GPU would run them; default: none).
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
# Logs: each run writes its log into SUITE_LOGS while it runs, every line led by the seconds since
# the run started (cmocka's "[ RUN      ]" and "[       OK ]" lines thus time each test), and the
# log is printed as soon as that run ends. A run stopped by SUITE_TIMEOUT or killed keeps what it
# wrote (tests/util_suite.c makes each suite's output line-buffered). SUITE_LOGS also gets
# summary.txt: one row per run (suite, passed, failed, skipped, seconds, what went wrong), and
# runs.txt the same rows as "|"-separated fields, each written as its run ends.
#
# Crashes: a test that dies of a signal takes its process with it, or (SIGSEGV, SIGFPE, SIGILL,
# SIGBUS) cmocka catches the signal and goes on in a process whose GL context may be broken. Either
# way the crashing test is counted failed, by name, and every test after it runs again, each in a
# fresh process of its own (tests/util_suite.c: BG_TEST_LIST names the tests, CMOCKA_TEST_FILTER
# picks one), so that one crash costs one test.
#
# Counting: per test, from cmocka's lines. Both cmocka 1.1's summary ("[  PASSED  ] 3 test(s).")
# and cmocka 2.0's, which names the group ("[  PASSED  ] tests: 3 test(s)."), are read; failures
# are counted per failing test ("[  FAILED  ]" and "[  ERROR   ]" lines, a test that never ended);
# a run that fails with no failing test to name counts as one failure. check_counting holds the
# parser to sample lines of both forms.
#
# Mesa prints a two-line notice each time a context is made under MESA_GLSL_VERSION_OVERRIDE=110
# (README, "Run the tests"): it says nothing about this project, and one copy per context (over a
# hundred a run) buried the lines that do. Those two lines, and only those, are left out of what is
# shown (the kept logs hold them); the counts read the suites' whole output, and the close says how
# many were left out.

glsl_notice='implementation error: Invalid GLSL version in shading_language_version()'
glsl_notice_next='Please report at https://gitlab.freedesktop.org/mesa/mesa/-/issues'
# A kept log's line starts with its time stamp: seconds, two decimals, one space.
stamp_re='^ *[0-9][0-9]*[.][0-9][0-9] '

# Copies stdin to stdout without Mesa's GLSL-version notice: a line ending in $glsl_notice, and
# the report line right after it (a report line after anything else is kept). Time stamps are
# looked through.
drop_glsl_notice() {
	awk -v notice="$glsl_notice" -v next_line="$glsl_notice_next" -v stamp="$stamp_re" '
		{ line = $0; sub(stamp, "", line) }
		after_notice && line == next_line { after_notice = 0; next }
		{ after_notice = 0 }
		line ~ /^Mesa / && substr(line, length(line) - length(notice) + 1) == notice { after_notice = 1; next }
		{ print }'
}

# Prefixes each line of stdin with the seconds since $1 (date +%s.%N), as the line arrives: with
# perl's Time::HiRes, else python3, else a shell loop (a date process a line).
stamp_lines() {
	if perl -MTime::HiRes=time -e 1 2>/dev/null; then
		perl -MTime::HiRes=time -e '$| = 1; my $s = shift;
			while (my $l = <STDIN>) { chomp $l; printf "%8.2f %s\n", time - $s, $l }' "$1"
	elif command -v python3 >/dev/null 2>&1; then
		python3 -c 'import sys, time
s, i, o = float(sys.argv[1]), sys.stdin.buffer, sys.stdout.buffer
for l in iter(i.readline, b""):
    o.write(b"%8.2f " % (time.time() - s) + l.rstrip(b"\n") + b"\n")
    o.flush()' "$1"
	else
		start_cs=$(echo "$1" | tr -d . | cut -c1-12)
		while IFS= read -r line || [ -n "$line" ]; do
			now_cs=$(date +%s%N | cut -c1-12)
			cs=$((now_cs - start_cs))
			printf '%5d.%02d %s\n' $((cs / 100)) $((cs % 100)) "$line"
		done
	fi
}

# Reads a cmocka log (time stamps allowed) and prints one line:
# "passed failed skipped notices unfinished|failing test names". With $1, counts the tests up to and
# including that one only, from their own lines (the runs after it are not this process's to count).
# A test that started and never ended (its process died, or was stopped) is failed and "unfinished".
count_log() {
	awk -v upto="$1" -v stamp="$stamp_re" -v notice="$glsl_notice" '
		function count_of(l) { l = substr(l, 14); sub(/^.*: /, "", l); return l + 0 }
		function name_of(l) { return substr(l, 14) }
		{ line = $0; sub(stamp, "", line) }
		line ~ /^Mesa / && substr(line, length(line) - length(notice) + 1) == notice { notices++ }
		done { next }
		line ~ /^\[==========\] (.*: )?[0-9]+ test\(s\) run\./ { if (upto == "") summary = 1; else done = 1; next }
		summary && line ~ /^\[  PASSED  \] (.*: )?[0-9]+ test\(s\)/ { s_passed = count_of(line); next }
		summary && line ~ /^\[  SKIPPED \] (.*: )?[0-9]+ test\(s\)/ { s_skipped = count_of(line); next }
		summary && line ~ /^\[  FAILED  \] (.*: )?[0-9]+ test\(s\)/ { s_failed = count_of(line); next }
		summary { next }
		line ~ /^\[ RUN      \] / { current = name_of(line); running = 1; next }
		line ~ /^\[       OK \] / { passed++; running = 0 }
		line ~ /^\[  SKIPPED \] / { skipped++; running = 0 }
		line ~ /^\[  FAILED  \] / || (line ~ /^\[  ERROR   \] / && line !~ /^\[  ERROR   \] --- /) {
			failed++; names = names " " name_of(line); running = 0
		}
		upto != "" && !running && current == upto && line ~ /^\[ *(OK|SKIPPED|FAILED|ERROR) *\] / { done = 1 }
		END {
			if (running) { failed++; names = names " " current; unfinished = current }
			if (summary) {
				passed = s_passed; skipped = s_skipped
				if (s_failed > failed) failed = s_failed
			}
			printf "%d %d %d %d %s|%s\n", passed, failed, skipped, notices, unfinished, names
		}'
}

# The parser on samples: cmocka 1.1's lines, cmocka 2.0's (the group named), time stamps, a test
# that never ended, and counting up to a test. A broken parser fails the run rather than miscount.
check_counting() {
	v1="[==========] Running 4 test(s).
[ RUN      ] a
[       OK ] a
[ RUN      ] b
[  ERROR   ] --- 0x4 != 0x5
[   LINE   ] --- x.c:1: error: Failure!
[  FAILED  ] b
[ RUN      ] c
[  SKIPPED ] c
[ RUN      ] d
[  ERROR   ] --- Test teardown failed
[  ERROR   ] d
[==========] 4 test(s) run.
[  PASSED  ] 1 test(s).
[  SKIPPED ] 1 test(s), listed below:
[  SKIPPED ] c

 1 SKIPPED TEST(S)
[  FAILED  ] 1 test(s), listed below:
[  FAILED  ] b

 2 FAILED TEST(S)"
	v2="[==========] tests: Running 3 test(s).
[ RUN      ] a
[       OK ] a
[ RUN      ] b
[       OK ] b
[ RUN      ] c
[  FAILED  ] c
[==========] tests: 3 test(s) run.
[  PASSED  ] tests: 2 test(s).
[  FAILED  ] tests: 1 test(s), listed below:
[  FAILED  ] c

 1 FAILED TEST(S)"
	died="[==========] Running 3 test(s).
[ RUN      ] a
[       OK ] a
[ RUN      ] b
Mesa 22.3.6 $glsl_notice"
	stamped=$(printf '%s\n' "$v2" | awk '{ printf "%8.2f %s\n", NR / 10, $0 }')
	[ "$(printf '%s\n' "$v1" | count_log)" = "1 2 1 0 | b d" ] &&
		[ "$(printf '%s\n' "$v2" | count_log)" = "2 1 0 0 | c" ] &&
		[ "$(printf '%s\n' "$stamped" | count_log)" = "2 1 0 0 | c" ] &&
		[ "$(printf '%s\n' "$died" | count_log)" = "1 1 0 1 b| b" ] &&
		[ "$(printf '%s\n' "$v1" | count_log b)" = "1 1 0 0 | b" ]
}

# The filter on a sample, with and without time stamps: the notice goes, everything else (another
# Mesa error, a report line of its own, cmocka's lines) stays. A broken filter fails the run rather
# than hide a line.
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
	stamp() { awk '{ printf "%8.2f %s\n", NR / 100, $0 }'; }
	[ "$(printf '%s\n' "$sample" | drop_glsl_notice)" = "$kept" ] &&
		[ "$(printf '%s\n' "$sample" | stamp | drop_glsl_notice | sed "s/$stamp_re//")" = "$kept" ]
}

# One program run of a suite: $1 the log it appends to, $2 the shader cache folder, $3 extra
# settings (NAME=value words), then the command (the debugger's, or none) before the binary. Leaves
# its exit status in $work_dir/last.status.$$ and returns it.
run_program() {
	rp_log=$1 rp_cache=$2 rp_extra=$3
	shift 3
	cache_env="MESA_SHADER_CACHE_DISABLE=false MESA_SHADER_CACHE_DIR=$rp_cache"
	[ "$SHADER_CACHE" = no ] && cache_env="MESA_SHADER_CACHE_DISABLE=true"
	limit=""
	[ -n "$SUITE_TIMEOUT" ] && limit="timeout -k 5 $SUITE_TIMEOUT"
	run_start=$(date +%s.%N)
	# shellcheck disable=SC2086 # TEST_ENV, cache_env, settings, rp_extra, limit are lists of words
	{
		env $TEST_ENV $cache_env $settings $rp_extra $limit "$@" "$binary" 2>&1 </dev/null
		echo $? >"$work_dir/last.status.$$"
	} | stamp_lines "$run_start" >>"$rp_log"
	rm -rf "$rp_cache"
	return "$(cat "$work_dir/last.status.$$")"
}

# The suite's test names, in order (tests/util_suite.c); nothing from a program without that hook,
# which would run its tests instead: hence the time limit.
list_tests() {
	limit=""
	command -v timeout >/dev/null 2>&1 && limit="timeout -k 2 10"
	# shellcheck disable=SC2086 # limit, TEST_ENV and settings are lists of words
	$limit env $TEST_ENV $settings BG_TEST_LIST=1 "$binary" 2>/dev/null </dev/null | sed -n 's/^bg-test: //p'
}

# Whether a run with exit status $1 and log $2 crashed: cmocka caught a signal in a test, or the
# process died of one (SIGKILL is a crash only where no SUITE_TIMEOUT sends it).
is_crash() {
	grep -q 'Test failed with exception: ' "$2" && return 0
	[ -n "$SUITE_TIMEOUT" ] && { [ "$1" = 124 ] || [ "$1" = 137 ]; } && return 1
	[ "$1" -gt 128 ]
}

# What a non-zero exit status means, for the log and the table.
describe_status() {
	if [ -n "$SUITE_TIMEOUT" ] && { [ "$1" = 124 ] || [ "$1" = 137 ]; }; then
		echo "timed out after $SUITE_TIMEOUT s"
	elif [ "$1" -gt 128 ]; then
		echo "died of SIG$(kill -l $(($1 - 128)) 2>/dev/null || echo "nal $(($1 - 128))")"
	else
		echo "exit status $1"
	fi
}

# One run of the list: "id|label|binary|settings...". Runs it with its own shader cache, writes its
# log into $log_dir as it goes, prints it when it ends, and leaves its counts in $work_dir/id.result.
if [ "$1" = "--one" ]; then
	IFS='|' read -r id label binary settings <<EOF
$2
EOF
	slug=$(printf '%s' "$label" | tr -c 'A-Za-z0-9_.' '-' | sed 's/--*/-/g; s/-$//')
	log="$log_dir/$id-$slug.log"
	start=$(date +%s.%N)
	echo "== $label: $binary $settings" >"$log"
	# shellcheck disable=SC2086 # RUN_WITH is a command line
	run_program "$log" "$work_dir/$id.cache" "" $RUN_WITH
	status=$?
	counts=$(count_log <"$log")
	unfinished=$(echo "$counts" | cut -d'|' -f1 | cut -d' ' -f5)
	what=""
	[ "$status" -gt 128 ] || [ "$status" = 124 ] && what=$(describe_status "$status")
	[ -n "$unfinished" ] && what="$what in $unfinished"
	crashed=""
	if is_crash "$status" "$log"; then
		# The first test that crashed: the one cmocka caught a signal in, else the one that never ended.
		crashed=$(sed "s/$stamp_re//" "$log" | awk '
			/^\[ RUN      \] / { t = substr($0, 14) }
			/Test failed with exception: / && t != "" { print t; exit }')
		if [ -n "$crashed" ]; then
			what="${what:+$what; }$crashed crashed (cmocka caught its signal)"
		else
			crashed=$unfinished
		fi
	fi
	if [ -n "$crashed" ]; then
		counts=$(count_log "$crashed" <"$log")
		names=$(list_tests)
		after=$(printf '%s\n' "$names" | awk -v c="$crashed" 'seen { print } $0 == c { seen = 1 }')
		if [ -z "$names" ]; then
			what="$what; the tests after it cannot be named (BG_TEST_LIST: tests/util_suite.c) and did not run again"
		elif [ -n "$after" ]; then
			what="$what; the $(printf '%s\n' "$after" | wc -l | tr -d ' ') tests after it ran again, each in a fresh process"
		fi
		crashes="$crashed"
		r=0
		for t in $after; do
			r=$((r + 1))
			rlog="$work_dir/$id.rerun$r.log"
			echo "== $label: $t again, alone in a fresh process" >"$rlog"
			# shellcheck disable=SC2086 # RUN_WITH is a command line
			run_program "$rlog" "$work_dir/$id.cache$r" "CMOCKA_TEST_FILTER=$t" $RUN_WITH
			rstatus=$?
			rcounts=$(count_log <"$rlog")
			is_crash "$rstatus" "$rlog" && crashes="$crashes $t"
			rf=$(echo "$rcounts" | cut -d' ' -f2)
			if [ "$rstatus" != 0 ] && [ "$rf" = 0 ]; then
				rcounts=$(echo "$rcounts" | awk -v t="$t" '{ $2 = 1; sub(/\|.*/, "| " t); print }')
				what="$what; $t: $(describe_status "$rstatus")"
			fi
			counts=$(printf '%s\n%s\n' "$counts" "$rcounts" | awk -F'|' '
				{ split($1, c, " "); for (i = 1; i <= 4; i++) s[i] += c[i]; names = names $2 }
				END { printf "%d %d %d %d |%s\n", s[1], s[2], s[3], s[4], names }')
			cat "$rlog" >>"$log"
		done
		# A backtrace of each test that crashed (at most 3 a suite), from a run of that test alone.
		if [ -n "$BACKTRACE" ]; then
			b=0
			for t in $crashes; do
				b=$((b + 1))
				[ $b -gt 3 ] && break
				echo "== $label: $t alone under $BACKTRACE, for a backtrace" >>"$log"
				# shellcheck disable=SC2086 # BACKTRACE is a command line
				run_program "$log" "$work_dir/$id.cachebt$b" "CMOCKA_TEST_FILTER=$t" $BACKTRACE
			done
		fi
	elif [ -n "$unfinished" ]; then
		# Stopped (SUITE_TIMEOUT) in a test: say how many tests never ran.
		left=$(list_tests | awk -v c="$unfinished" 'seen { n++ } $0 == c { seen = 1 } END { print n + 0 }')
		[ "$left" != 0 ] && what="$what; $left tests after it did not run"
	fi
	p=$(echo "$counts" | cut -d' ' -f1)
	f=$(echo "$counts" | cut -d' ' -f2)
	s=$(echo "$counts" | cut -d' ' -f3)
	k=$(echo "$counts" | cut -d' ' -f4)
	failing=$(echo "$counts" | cut -d'|' -f2)
	if [ "$status" != 0 ] && [ -z "$crashed" ] && [ "$f" = 0 ]; then
		f=1
		[ -z "$what" ] && what=$(describe_status "$status")
		failing=" (the suite: $what)"
	fi
	end=$(date +%s.%N)
	secs=$(awk -v s="$start" -v e="$end" 'BEGIN { printf "%.1f", e - s }')
	echo "$id|$label|$p|$f|$s|$secs|$k|$what|$failing|$log" >"$work_dir/$id.result"
	# One run's report at a time, whole, however many runs end together.
	until mkdir "$work_dir/print.lock" 2>/dev/null; do sleep 0.1; done
	printf '%s|%s|%s|%s|%s|%s\n' "$label" "$p" "$f" "$s" "$secs" "$what" >>"$log_dir/runs.txt"
	echo "== $label ($secs s): $p passed, $f failed, $s skipped${what:+ ($what)}; log: $log"
	if [ "$SUITE_PRINT" != failures ] || [ "$f" != 0 ]; then
		drop_glsl_notice <"$log"
		[ "$f" != 0 ] && echo "-- failing in $label:$failing"
	fi
	rmdir "$work_dir/print.lock"
	exit 0
fi

suites=$1
smoke=$2
jobs=${CHECK_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
logs=${SUITE_LOGS:-build/suite-logs/$(date +%Y%m%d-%H%M%S)-$$}
mkdir -p "$logs" || exit 1
# In the default place, the last 10 runs' logs are kept.
[ -z "$SUITE_LOGS" ] && ls -1dt build/suite-logs/*/ 2>/dev/null | tail -n +11 |
	while read -r old; do rm -rf "$old"; done

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
if ! check_counting; then
	echo "run_suites.sh: the cmocka output parser miscounts its samples"
	broken="$broken count-parser"
	failed=$((failed + 1))
fi
if [ -n "$SUITE_TIMEOUT" ] && ! command -v timeout >/dev/null 2>&1; then
	echo "run_suites.sh: SUITE_TIMEOUT needs the timeout command (coreutils)"
	exit 1
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
	echo "$(printf '%02d' $n)|$1|$2|$3" >>"$work/list"
}
: >"$work/list"
for t in $suites; do
	add "$(basename "$t") ($main_name, ${main_driver:-llvmpipe})" "$t" "$main"
done
for t in $smoke; do
	[ -n "$other" ] && add "$(basename "$t") ($other_name, llvmpipe)" "$t" "$other"
	[ -n "$soft" ] && add "$(basename "$t") ($soft_name, softpipe)" "$t" "$soft"
done
# Under a profile a test the renderer refuses is skipped by cmocka's skip(), which jumps out of the
# test past its frees: LeakSanitizer would count what the test had made so far. Those runs check no
# leaks; the same suites' own runs, without a profile, keep leak checking on every path.
for p in $PROFILES; do
	for t in $PROFILE_SUITES; do
		add "$(basename "$t") ($main_name, ${main_driver:-llvmpipe}, profile $p)" "$t" \
			"$main MACS_TEST_PROFILE=$p ASAN_OPTIONS=detect_leaks=0"
	done
done

# Longest first, by the last run's times where TIMES keeps them, so that no long suite starts last.
if [ -n "$TIMES" ] && [ -f "$TIMES" ]; then
	awk -F'|' 'NR == FNR { t[$1] = $2; next } { print (($2 in t) ? t[$2] : 0) "|" $0 }' "$TIMES" "$work/list" |
		sort -t'|' -k1,1 -g -r | cut -d'|' -f2- >"$work/order"
else
	cp "$work/list" "$work/order"
fi

echo "== $n suite runs, $jobs at a time${SUITE_TIMEOUT:+, each stopped after $SUITE_TIMEOUT s}; logs in $logs"
tr '\n' '\0' <"$work/order" | work_dir="$work" log_dir="$logs" TEST_ENV="$TEST_ENV" RUN_WITH="$RUN_WITH" \
	SHADER_CACHE="$SHADER_CACHE" SUITE_TIMEOUT="$SUITE_TIMEOUT" SUITE_PRINT="$SUITE_PRINT" BACKTRACE="$BACKTRACE" \
	xargs -0 -P "$jobs" -n 1 sh "$0" --one

# The counts, in the list's order, and the table.
: >"$work/times"
printf '%-58s %6s %6s %7s %8s  %s\n' suite passed failed skipped seconds "" >"$logs/summary.txt"
while IFS='|' read -r id label binary settings; do
	if [ -f "$work/$id.result" ]; then
		IFS='|' read -r _ _ p f s secs k what failing log <"$work/$id.result"
	else
		p=0 f=1 s=0 secs="" k=0 what="not run" failing=""
	fi
	printf '%-58s %6d %6d %7d %8s  %s\n' "$label" "$p" "$f" "$s" "$secs" "$what" >>"$logs/summary.txt"
	echo "$label|$secs" >>"$work/times"
	passed=$((passed + p))
	failed=$((failed + f))
	skipped=$((skipped + s))
	notices=$((notices + k))
	[ "$f" != 0 ] && broken="$broken $label"
	echo "$((p + f + s))" >"$work/$id.tests"
done <"$work/list"
[ -n "$TIMES" ] && cp "$work/times" "$TIMES"

# Without OSMesa its smoke runs cannot happen: each counts its suite's tests as skipped.
if [ "$osmesa" = no ]; then
	for t in $smoke; do
		id=$(awk -F'|' -v b="$t" '$3 == b { print $1; exit }' "$work/list")
		k=$(cat "$work/$id.tests" 2>/dev/null)
		echo "== $(basename "$t") (OSMesa, llvmpipe and softpipe): skipped, OSMesa is not installed (${k:-0} tests each)"
		skipped=$((skipped + 2 * ${k:-0}))
	done
fi

echo
echo "== summary ($logs/summary.txt)"
cat "$logs/summary.txt"
[ "$notices" != 0 ] && echo "($notices Mesa notices \"Invalid GLSL version\" left out: README, \"Run the tests\")"
[ -n "$broken" ] && echo "failing suites:$broken"
echo "$passed passed, $failed failed, $skipped skipped" | tee "$logs/closing.txt"
[ "$failed" = 0 ] && [ -z "$broken" ]
