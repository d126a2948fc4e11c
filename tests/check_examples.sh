#!/bin/sh
# Runs the example programs the way a user first meets them. Every example must answer -h / --help
# with its usage on stdout (exit 0) and refuse an unknown option, a bad size and too many arguments
# (exit 2, naming on stderr the argument it refused), writing no file in any of those cases (an example once
# saved a PNG named "--help"). Each standalone example must also render and write a PNG, the GPU one
# under the test environment ($TEST_ENV).
# Usage: check_examples.sh "standalone example binaries" "other example binaries"
standalone=$1
others=$2
failed=""
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

fail() { # binary, what went wrong
	echo "FAIL $(basename "$1"): $2"
	failed="$failed $(basename "$1")"
}

# Runs binary with arguments in an empty folder, so that any file it writes shows; fills
# $status, $work/out and $work/err, and $written with what appeared in the folder.
run_in_empty() {
	rm -rf "$work/cwd" && mkdir "$work/cwd"
	bin=$1; shift
	if (cd "$work/cwd" && exec "$bin" "$@") >"$work/out" 2>"$work/err"; then status=0; else status=$?; fi
	written=$(ls -A "$work/cwd")
}

# The command line: --help, an unknown option, a size that is no number, too many arguments.
check_command_line() {
	bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
	name=$(basename "$1")
	run_in_empty "$bin" --help
	[ "$status" = 0 ] || { fail "$1" "--help exits $status, not 0"; return; }
	grep -q "^usage: $name " "$work/out" || { fail "$1" "--help prints no 'usage: $name' line"; return; }
	[ -z "$written" ] || { fail "$1" "--help wrote $written"; return; }
	run_in_empty "$bin" -h
	[ "$status" = 0 ] && [ -z "$written" ] || { fail "$1" "-h exits $status or writes a file"; return; }
	for args in "--bogus" "out.png --bogus" "out.png 12x" "a.png 64 extra"; do
		# shellcheck disable=SC2086 # the arguments are meant to split
		run_in_empty "$bin" $args
		[ "$status" = 2 ] || { fail "$1" "'$args' exits $status, not 2"; return; }
		named=""
		for a in $args; do
			[ "$a" != out.png ] && [ "$a" != a.png ] && grep -q -- "'$a'" "$work/err" && named=$a
		done
		[ -n "$named" ] || { fail "$1" "'$args': stderr names no argument: $(cat "$work/err")"; return; }
		[ -z "$written" ] || { fail "$1" "'$args' wrote $written"; return; }
	done
}

# A small render must give a PNG (its 8-byte signature) at the path given.
check_render() {
	png="$work/$(basename "$1").png"
	if ! env $TEST_ENV "$1" "$png" 48 >"$work/out" 2>"$work/err"; then
		fail "$1" "rendering failed:"; cat "$work/out" "$work/err"; return
	fi
	[ "$(head -c 8 "$png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
		{ fail "$1" "wrote no PNG at $png"; return; }
	sed 's/^/   /' "$work/out" # stdout only: on success stderr holds Mesa's notices (README)
}

for b in $standalone; do
	check_command_line "$b"
	check_render "$b"
done
for b in $others; do
	check_command_line "$b"
done
# The window example (examples/bg_window.c) in a window of its own X server: a few frames, then its
# PNG. Without Xvfb it is said and skipped (CI installs it: .ci/run).
window_ran=""
for b in $others; do
	[ "$(basename "$b")" = bg_window ] || continue
	if ! command -v xvfb-run >/dev/null 2>&1; then
		echo "SKIPPED bg_window in a window: no xvfb-run (apt-get install xvfb xauth)"
		continue
	fi
	png="$work/bg_window.png"
	# Mesa's GLX driver leaks a few KB and is unloaded before LeakSanitizer runs, leaving frames no
	# suppression can name: leaks are not looked for here (a sanitized build's memory errors still are).
	if ! env $TEST_ENV ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" xvfb-run -a -s "-screen 0 640x480x24" "$b" --frames 5 "$png" 48 >"$work/out" 2>"$work/err"; then
		fail "$b" "5 frames under Xvfb failed:"; cat "$work/out" "$work/err"; continue
	fi
	[ "$(head -c 8 "$png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
		{ fail "$b" "wrote no PNG after 5 frames"; continue; }
	sed 's/^/   /' "$work/out"
	window_ran=", bg_window ran 5 frames under Xvfb"
done
count=$(echo $standalone $others | wc -w)
if [ -n "$failed" ]; then
	echo "examples failing:$failed"
	exit 1
fi
echo "examples: $count checked (--help, unknown option, bad size, too many arguments), standalone ones rendered$window_ran"
