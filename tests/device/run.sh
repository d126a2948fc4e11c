#!/bin/sh
# The device check, the one command on a machine with a GPU (docs/device_check.md): made by
# `make device-pack` as build/device/run.sh beside payload.tar.xz and debs/, it
#  1. unpacks the payload (xz, else python3) into DEVICE_CHECK_DIR, anywhere;
#  2. makes EGL work there: glvnd's packages (debs/) unpacked where the machine has no libEGL.so.1
#     (into / as root, as the device tool's README does, else into a private folder), and NVIDIA's
#     EGL vendor file named where it exists;
#  3. prints the machine, the driver (nvidia-smi), GL's vendor, renderer and version and the limits
#     (tests/device/device_info);
#  4. checks the runner's crash handling there (tests/device/check_runner.sh, under gdb or cuda-gdb);
#  5. runs every suite on the EGL device through tests/run_suites.sh (SUITE_BACKEND=device),
#     CHECK_JOBS at a time, each stopped after SUITE_TIMEOUT s, each log kept as it ends, the tests
#     after a crash run again in fresh processes and each crashed test run once more under the
#     debugger for its backtrace;
#  6. runs bench_frame_cost, bench_paper and bench_distribution (QUICK=1);
#  7. writes summary.txt (suite, passed, failed, skipped, seconds) and packs everything into one
#     archive in $OUT (default ./device-check-out), with summary.txt beside it.
# Every step has its time limit inside DEVICE_CHECK_SECONDS (default 450), and the archive is made
# whatever happened before it.
# Environment: OUT, DEVICE_CHECK_SECONDS, DEVICE_CHECK_DIR (default $TMPDIR or /tmp, then
# betelgeuse-device-check), CHECK_JOBS (default 4), SUITE_TIMEOUT (default 150), SUITES (suite
# names to run, such as "test_macs_pass test_bg_gpu_mesh"; default every one), BENCH (no: skip the
# benchmarks), DEVICE_BACKEND (the backend device_info reports on; default device).
set -u
budget=${DEVICE_CHECK_SECONDS:-450}
t0=$(date +%s)
left() { echo $((budget - ($(date +%s) - t0))); }
pack=$(cd "$(dirname "$0")" && pwd)
work=${DEVICE_CHECK_DIR:-${TMPDIR:-/tmp}/betelgeuse-device-check}
out=${OUT:-$PWD/device-check-out}
stamp=$(date -u +%Y%m%d-%H%M%S)
name="device-check-$stamp"

rm -rf "$work"
mkdir -p "$work" "$out" || exit 1
if command -v xz >/dev/null 2>&1; then
	xz -dc "$pack/payload.tar.xz" | tar xf - -C "$work"
elif command -v python3 >/dev/null 2>&1; then
	python3 -c 'import sys, tarfile
t = tarfile.open(sys.argv[1])
try:
    t.extractall(sys.argv[2], filter="tar")
except TypeError:
    t.extractall(sys.argv[2])' "$pack/payload.tar.xz" "$work"
else
	echo "device check: neither xz nor python3 here to unpack $pack/payload.tar.xz"
	exit 1
fi
root="$work/betelgeuse-device"
[ -x "$root/bin/betelgeuse" ] || { echo "device check: $pack/payload.tar.xz did not unpack"; exit 1; }
res="$work/$name"
mkdir -p "$res"
cd "$root" || exit 1

# The debugger for backtraces: gdb, else cuda-gdb (which debugs programs without GPU code too).
bt=""
for d in gdb cuda-gdb; do
	command -v $d >/dev/null 2>&1 && bt="$d -batch -ex run -ex bt --args" && break
done
test_env="MESA_GL_VERSION_OVERRIDE=2.1 MESA_GLSL_VERSION_OVERRIDE=110 MESA_SHADER_CACHE_DISABLE=true"

main() {
	echo "== device check ($(sed -n 's/^commit: //p' manifest.txt)), $(date -u '+%Y-%m-%d %H:%M:%S UTC'), $budget s"
	echo "machine: $(uname -m), kernel $(uname -r), $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME")," \
		"glibc $(getconf GNU_LIBC_VERSION 2>/dev/null | cut -d' ' -f2), $(getconf _NPROCESSORS_ONLN) processors"
	sed -n 's/^needs: /pack needs: /p' manifest.txt
	if command -v nvidia-smi >/dev/null 2>&1; then
		nvidia-smi >"$res/nvidia-smi.txt" 2>&1
		echo "driver: $(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>&1 | head -n4)"
	else
		echo "driver: no nvidia-smi here"
	fi

	# glvnd's libEGL.so.1, where the machine has none.
	if ldconfig -p 2>/dev/null | grep -q 'libEGL\.so\.1 '; then
		echo "libEGL.so.1: the machine's own"
	elif ls "$pack"/debs/*.deb >/dev/null 2>&1 && command -v dpkg >/dev/null 2>&1; then
		if [ "$(id -u)" = 0 ]; then
			for f in "$pack"/debs/*.deb; do dpkg -x "$f" /; done
			ldconfig
			echo "libEGL.so.1: glvnd from debs/ unpacked into / ($(ls "$pack"/debs | tr '\n' ' '))"
		else
			for f in "$pack"/debs/*.deb; do dpkg -x "$f" "$work/glvnd"; done
			LD_LIBRARY_PATH="$work/glvnd/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
			echo "libEGL.so.1: glvnd from debs/ in $work/glvnd (not root)"
		fi
	else
		echo "libEGL.so.1: none here, and no glvnd packages in $pack/debs: no EGL context will be made"
	fi
	nv_json=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
	if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -f "$nv_json" ]; then
		__EGL_VENDOR_LIBRARY_FILENAMES=$nv_json
		export __EGL_VENDOR_LIBRARY_FILENAMES
	fi
	echo "EGL vendor files: ${__EGL_VENDOR_LIBRARY_FILENAMES:-glvnd's default folders}"
	for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do
		[ -d "$d" ] && LD_LIBRARY_PATH="${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$d"
	done

	# The packed libraries first; the toolchain's runtime only where the machine's cannot serve.
	LD_LIBRARY_PATH="$root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
	export LD_LIBRARY_PATH
	if ! bin/betelgeuse --version >/dev/null 2>&1; then
		LD_LIBRARY_PATH="$root/lib:$root/lib/fallback:$LD_LIBRARY_PATH"
		if bin/betelgeuse --version >/dev/null 2>&1; then
			echo "libraries: the packed libstdc++ and libgcc_s (lib/fallback) in use"
		else
			echo "libraries: the packed programs do not load here:"
			ldd bin/betelgeuse 2>&1 | grep -v '=> /' | head -n8
			bin/betelgeuse --version 2>&1 | head -n3
		fi
	fi

	echo "libraries: $(ldd bin/tests/test_scenefile_models bin/betelgeuse 2>/dev/null | grep -c "=> $root/lib/") loaded from" \
		"the pack's lib/, $(ldd bin/tests/test_scenefile_models bin/betelgeuse 2>/dev/null | grep -c 'not found') not found"

	echo
	echo "== GL (device_info ${DEVICE_BACKEND:-device})"
	# shellcheck disable=SC2086 # test_env is a list of NAME=value words
	timeout -k 5 60 env $test_env bin/tests/device/device_info "${DEVICE_BACKEND:-device}" >"$res/gl-info.txt" 2>&1
	echo "(exit status $?)" >>"$res/gl-info.txt"
	grep -v '^GL_EXTENSIONS: ' "$res/gl-info.txt" | grep -v '^Mesa .*shading_language_version()$\|^Please report at '
	echo "GL_EXTENSIONS: $(sed -n 's/^GL_EXTENSIONS: //p' "$res/gl-info.txt" | wc -w) (gl-info.txt lists them)"

	echo
	echo "== the runner on a suite that crashes on purpose${bt:+ (backtraces: ${bt%% *})}"
	BACKTRACE="$bt" timeout -k 5 120 sh tests/device/check_runner.sh bin/tests/device/crash_suite "$res/runner-check"

	echo
	bench_reserve=0
	[ "${BENCH:-yes}" = no ] || bench_reserve=170
	suite_secs=$(($(left) - bench_reserve - 15))
	if [ -n "${SUITES:-}" ]; then
		suites=$(for s in $SUITES; do printf '%s ' "bin/tests/$s"; done)
	else
		suites=$(ls bin/tests/test_* | tr '\n' ' ')
	fi
	# The last local run's times, under this run's labels, so that the longest suites start first.
	if [ -f suite-times ]; then
		sed 's/ (.*|/ (EGL device, the device'"'"'s driver)|/' suite-times >"$work/times"
	fi
	echo "== suites on the EGL device: $(echo "$suites" | wc -w), ${CHECK_JOBS:-4} at a time," \
		"each within ${SUITE_TIMEOUT:-150} s, all within $suite_secs s"
	if [ "$suite_secs" -gt 10 ]; then
		# Each run's line as it ends; its log (and a failing run's whole output) in the archive.
		{
			TEST_ENV="$test_env" SUITE_BACKEND=device CHECK_JOBS=${CHECK_JOBS:-4} SUITE_TIMEOUT=${SUITE_TIMEOUT:-150} \
				SUITE_PRINT=failures SUITE_LOGS="$res/suites" BACKTRACE="$bt" TIMES="$work/times" \
				timeout -k 10 "$suite_secs" sh tests/run_suites.sh "$suites" "" 2>&1
			echo $? >"$work/suites.status"
		} | tee "$res/suites.txt" | grep --line-buffered '^== .* passed, .* failed, .* skipped\|^-- failing in ' |
			sed -u "s/ (EGL device, the device's driver)//; s/; log: [^ ]*\$//"
		suites_status=$(cat "$work/suites.status")
		[ "$suites_status" = 124 ] || [ "$suites_status" = 137 ] &&
			echo "(the suites ran past $suite_secs s and were stopped: the runs that ended are counted)" |
			tee "$res/suites-stopped.txt"
	else
		echo "no time left for the suites (DEVICE_CHECK_SECONDS=$budget)" | tee "$res/suites-stopped.txt"
	fi

	if [ "${BENCH:-yes}" != no ]; then
		mkdir -p "$res/bench"
		for b in bench_frame_cost bench_paper bench_distribution; do
			# bench_frame_cost gets a third of what is left, bench_paper half the rest, bench_distribution
			# the rest.
			secs=$(($(left) - 15))
			[ "$b" = bench_frame_cost ] && secs=$((secs / 3))
			[ "$b" = bench_paper ] && secs=$((secs / 2))
			echo
			echo "== $b (QUICK=1, within $secs s)"
			if [ "$secs" -lt 10 ]; then
				echo "no time left"
				continue
			fi
			# shellcheck disable=SC2086 # test_env is a list of NAME=value words
			timeout -k 5 "$secs" env $test_env QUICK=1 MACS_TEST_BACKEND=device "bin/bench/$b" "$res/bench" \
				>"$res/bench/$b.txt" 2>"$res/bench/$b.err"
			st=$?
			grep -v '^Mesa .*shading_language_version()$\|^Please report at ' "$res/bench/$b.txt" | tail -n 12
			echo "$b: $([ $st = 0 ] && echo done || echo "exit status $st$([ $st = 124 ] && echo ", stopped after $secs s")")," \
				"table in bench/$b.txt" | tee "$res/bench/$b.status"
		done
	fi
}

main 2>&1 | tee "$res/device-check.log"

# The table, from the suites that ended (runs.txt is written as each ends), and the archive.
{
	grep -v '^GL_EXTENSIONS: \|^Mesa \|^Please report' "$res/gl-info.txt" 2>/dev/null | head -n 12
	echo
	printf '%-50s %6s %6s %7s %8s  %s\n' suite passed failed skipped seconds ""
	if [ -f "$res/suites/runs.txt" ]; then
		sort "$res/suites/runs.txt" | awk -F'|' '{
			sub(/ \(EGL device, the device.s driver\)/, "", $1)
			printf "%-50s %6d %6d %7d %8s  %s\n", $1, $2, $3, $4, $5, $6
			p += $2; f += $3; s += $4; n++ }
			END { printf "%d suites: %d passed, %d failed, %d skipped\n", n, p, f, s }'
	fi
	tail -n1 "$res/suites.txt" 2>/dev/null | grep 'passed, .* failed' | sed 's/^/run_suites.sh: /'
	cat "$res/suites-stopped.txt" 2>/dev/null
	cat "$res/bench/bench_frame_cost.status" "$res/bench/bench_paper.status" "$res/bench/bench_distribution.status" 2>/dev/null
} >"$res/summary.txt"
echo
echo "== summary"
cat "$res/summary.txt"
tar czf "$out/$name.tar.gz" -C "$work" "$name"
cp "$res/summary.txt" "$out/$name-summary.txt"
echo "== archive: $out/$name.tar.gz ($(du -h "$out/$name.tar.gz" | cut -f1)), in $(($(date +%s) - t0)) s"
tail -n1 "$res/suites.txt" 2>/dev/null | grep -q '^[0-9]* passed, 0 failed'
