#!/bin/sh
# make check-view: `betelgeuse view` end to end in a real window (docs/command.md, "view"), on Xvfb
# with Mesa's GLX (llvmpipe) under the test environment's GL 2.1 / GLSL 1.10. Scripts drive the
# viewer's own input functions; xdotool drives the real window. Every check prints what failed; the
# first failure stops the script with exit 1. Without xvfb-run every check is skipped, said, and
# counted.
#   usage: tests/check_view.sh BUILD/betelgeuse
set -u
cli=$1
case $cli in /*) ;; *) cli=$PWD/$cli ;; esac
root=$(cd "$(dirname "$0")/.." && pwd)
json=$root/examples/scenes/json
out=$(mktemp -d /tmp/betelgeuse-view.XXXXXX)
checks=0
started=$(date +%s)

if ! command -v xvfb-run >/dev/null 2>&1 || ! command -v Xvfb >/dev/null 2>&1; then
	echo "check-view: SKIPPED 11 checks: no xvfb-run/Xvfb (Debian: apt-get install xvfb xauth xdotool)"
	rm -rf "$out"
	exit 0
fi

fail() {
	echo "check-view: FAILED: $*" >&2
	exit 1
}
trap '[ -n "${KEEP:-}" ] || rm -rf "$out"' EXIT

# Mesa notes the forced GLSL 1.10 on stderr; those lines are not the viewer's.
own_stderr() {
	grep -v -e 'Invalid GLSL version' -e 'gitlab.freedesktop.org/mesa' "$1"
}

# view CODE DESCRIPTION ARGS...: the viewer in a window of its own X server; stdout in $out/stdout,
# stderr (Mesa's notes left out) in $out/err; the exit code must be CODE.
view() {
	code=$1
	what=$2
	shift 2
	xvfb-run -a -s "-screen 0 640x480x24" "$cli" view "$@" >"$out/stdout" 2>"$out/err.all"
	got=$?
	own_stderr "$out/err.all" >"$out/err"
	checks=$((checks + 1))
	[ "$got" = "$code" ] || fail "$what: exit $got, want $code; stdout: $(cat "$out/stdout"); stderr: $(cat "$out/err")"
}

# script NAME LINES...: a script file made of the lines given.
script() {
	name=$1
	shift
	printf '%s\n' "$@" >"$out/$name"
}

echo "== check-view: $cli"

# 1. The command line: --help lists every option and key; bad usage exits 2 and names what it refused.
"$cli" --help >"$out/help" || fail "--help"
for word in "betelgeuse view" --frame-ms --script --benchmark --integrator "left drag" "right or middle drag" wheel " F " " R " " P " " I " Esc; do
	grep -qF -- "$word" "$out/help" || fail "--help does not mention '$word'"
done
checks=$((checks + 1))
"$cli" view "$json/glass.json" -o x.png 2>"$out/err" && fail "view -o is accepted"
grep -qF -- "-o is an option of render" "$out/err" || fail "view -o: $(cat "$out/err")"
"$cli" view "$json/glass.json" --frame-ms 0 2>"$out/err" && fail "--frame-ms 0 is accepted"
grep -qF -- "--frame-ms: '0'" "$out/err" || fail "--frame-ms 0: $(cat "$out/err")"
script bad.txt "wait 10" "# a comment" "jump 3"
"$cli" view "$json/glass.json" --script "$out/bad.txt" 2>"$out/err"
[ $? = 2 ] || fail "a bad script does not exit 2"
grep -qF "bad.txt:3: unknown command 'jump'" "$out/err" || fail "a bad script's message: $(cat "$out/err")"
checks=$((checks + 1))

# 2. A GL 2.1 context; at rest after N samples the screenshot is `render --samples N`'s file, byte for
#    byte, and no frame is drawn once the N samples are there.
size=64x48
samples=4
"$cli" render "$json/paper_earth_shadow.json" --size $size --samples $samples -o "$out/render.png" --quiet \
	2>/dev/null || fail "render paper_earth_shadow"
script rest.txt "expect-gl 2.1" "wait-rest" "screenshot $out/rest.png" "expect-compiled any" "wait 300" \
	"drag left 10 24 50 24 5" "wait-rest" "expect-compiled 0" "screenshot $out/dragged.png" "quit"
view 0 "rest, screenshot, drag" "$json/paper_earth_shadow.json" --size $size --samples $samples --script "$out/rest.txt"
cmp -s "$out/render.png" "$out/rest.png" || fail "the screenshot at rest after $samples samples differs from render's"
grep -q "frames drawn at rest after $samples samples: 0" "$out/stdout" || fail "frames at rest: $(cat "$out/stdout")"
grep -q "frames drawn: [1-9][0-9]* moving" "$out/stdout" || fail "the drag drew no moving frame: $(cat "$out/stdout")"
cmp -s "$out/rest.png" "$out/dragged.png" && fail "a left drag left the image as it was"
echo "   the screenshot after $samples samples is render's file; a drag moved the view, compiling nothing"

# 3. Reload on edit: a material value edit shows and compiles nothing; a broken edit keeps the image and
#    names file, JSON path and reason as render does; the fix recovers.
scene=$out/edit.json
red='{"materials": {"m": {"base": {"reflectance": [0.8, 0.1, 0.1]}}}, "lights": [{"position": [3, 6, 4]}], "objects": [{"sphere": {"center": [0, 0, -3], "radius": 1}, "material": "m"}]}'
blue='{"materials": {"m": {"base": {"reflectance": [0.1, 0.1, 0.8]}}}, "lights": [{"position": [3, 6, 4]}], "objects": [{"sphere": {"center": [0, 0, -3], "radius": 1}, "material": "m"}]}'
broken='{"materials": {"m": {"base": {"reflectance": [0.1, 0.1, 0.8]}}}, "lights": [{"position": [3, 6, 4]}], "objects": [{"sphere": {"center": [0, 0, -3], "radius": -1}, "material": "m"}]}'
printf '%s\n' "$broken" >"$out/broken.json"
"$cli" render "$out/broken.json" -o "$out/broken.png" --renderer cpu 2>"$out/render_err"
render_message=$(sed "s|$out/broken.json|$scene|" "$out/render_err")
printf '%s\n' "$red" >"$scene"
script edit.txt "wait-rest" "screenshot $out/red.png" "expect-compiled any" \
	"write $scene $blue" "wait-reload" "expect-error none" "wait-rest" "expect-compiled 0" "screenshot $out/blue.png" \
	"write $scene $broken" "wait-reload" "expect-error objects[0].sphere.radius" "screenshot $out/kept.png" \
	"write $scene $red" "wait-reload" "expect-error none" "wait-rest" "screenshot $out/fixed.png" "quit"
view 0 "edits of the scene" "$scene" --size $size --samples 2 --script "$out/edit.txt"
cmp -s "$out/red.png" "$out/blue.png" && fail "the colour edit did not show"
cmp -s "$out/blue.png" "$out/kept.png" || fail "the broken edit did not keep the last image"
cmp -s "$out/red.png" "$out/fixed.png" || fail "fixing the file did not bring the first image back"
grep -qxF -- "$render_message" "$out/err" || fail "the broken edit's message is not render's '$render_message': $(cat "$out/err")"
grep -q "reloads: 2, failed: 1" "$out/stdout" || fail "reload counts: $(cat "$out/stdout")"
echo "   a colour edit showed (no program compiled), a broken one kept the image with render's message, the fix recovered"

# 4. Esc through the script exits 0, and the process is gone.
script esc.txt "wait-rest" "key ESC" "wait 5000" "screenshot $out/never.png"
view 0 "Esc" "$json/glass.json" --size 32x24 --samples 1 --script "$out/esc.txt"
[ -e "$out/never.png" ] && fail "the script went on after Esc"

# 5. The real window under xdotool: found by its title, a drag, P saves a screenshot, Escape quits (exit
#    0) and no process is left.
cat >"$out/xdotool.sh" <<XEOF
cd "$out"
"$cli" view "$json/paper_earth_shadow.json" --size $size --samples 2 -v >"$out/x_stdout" 2>"$out/x_err" &
pid=\$!
w=""
for i in \$(seq 100); do w=\$(xdotool search --name '^betelgeuse view' 2>/dev/null | head -n1); [ -n "\$w" ] && break; sleep 0.1; done
[ -n "\$w" ] || { echo "no window titled 'betelgeuse view'"; kill \$pid; exit 1; }
for i in \$(seq 100); do xdotool getwindowname \$w | grep -q 'at rest' && break; sleep 0.1; done
xdotool mousemove --window \$w 10 20 mousedown 1 mousemove --window \$w 30 22 mousemove --window \$w 50 26 mouseup 1
sleep 0.5
xdotool key --window \$w p
for i in \$(seq 50); do [ -e betelgeuse-view-1.png ] && break; sleep 0.1; done
xdotool key --window \$w Escape 2>/dev/null
for i in \$(seq 100); do kill -0 \$pid 2>/dev/null || break; sleep 0.1; done
kill -0 \$pid 2>/dev/null && { echo "the viewer (pid \$pid) is still running after Escape"; kill \$pid; exit 1; }
wait \$pid
echo "exit \$?"
XEOF
xvfb-run -a -s "-screen 0 640x480x24" sh "$out/xdotool.sh" >"$out/x_result" 2>&1
checks=$((checks + 1))
grep -q "^exit 0$" "$out/x_result" || fail "xdotool: $(cat "$out/x_result") $(own_stderr "$out/x_err")"
[ -s "$out/betelgeuse-view-1.png" ] || fail "xdotool: key p saved no betelgeuse-view-1.png"
grep -q "frames drawn: [1-9][0-9]* moving" "$out/x_stdout" || fail "xdotool: the drag drew no moving frame: $(cat "$out/x_stdout")"
echo "   xdotool: the window found by title, a drag, p saved a screenshot, Escape quit (exit 0), no process left"

# 6. The integrator: I switches to path and back, and back at Whitted the frame at rest is the first one
#    byte for byte. --integrator path starts the viewer on path: its frame at rest is render's (GPU)
#    file, or, while no GPU plan draws path, the GPU's refusal is shown (naming the integrator and the
#    CPU renderer) and rendering goes on after I.
script integrator.txt "wait-rest" "screenshot $out/whitted.png" "key I" "wait 300" "screenshot $out/path.png" \
	"key i" "wait-rest" "expect-error none" "screenshot $out/back.png" "quit"
view 0 "the I key" "$json/glass.json" --size $size --samples 2 --script "$out/integrator.txt"
cmp -s "$out/whitted.png" "$out/back.png" || fail "I twice did not bring Whitted's frame back"
if grep -qF "BG_INTEGRATOR_PATH" "$out/err"; then
	grep -qF -- "--renderer cpu" "$out/err" || fail "the GPU's refusal of path does not name --renderer cpu: $(cat "$out/err")"
	said_path="the GPU's refusal of path shown"
	script path.txt "wait 300" "expect-error BG_INTEGRATOR_PATH" "key I" "wait-rest" "expect-error none" "quit"
	view 0 "--integrator path" "$json/glass.json" --size $size --samples 2 --integrator path --script "$out/path.txt"
else
	cmp -s "$out/whitted.png" "$out/path.png" && fail "I left the frame as it was"
	"$cli" render "$json/glass.json" --size $size --samples 2 --integrator path -o "$out/render_path.png" --quiet \
		2>/dev/null || fail "render --integrator path (gpu)"
	script path.txt "wait-rest" "expect-error none" "screenshot $out/rest_path.png" "quit"
	view 0 "--integrator path" "$json/glass.json" --size $size --samples 2 --integrator path --script "$out/path.txt"
	cmp -s "$out/render_path.png" "$out/rest_path.png" || fail "--integrator path at rest differs from render's file"
	said_path="path at rest is render's file"
fi
echo "   I switched to path and back to the same frame; $said_path"

echo "check-view: $checks checks passed in $(($(date +%s) - started)) s"
