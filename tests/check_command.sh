#!/bin/sh
# make check-command: the `betelgeuse` command end to end (docs/command.md). Every check prints what
# it ran; the first failure stops the script with exit 1.
#   usage: tests/check_command.sh BUILD/betelgeuse
set -u
cli=$1
root=$(cd "$(dirname "$0")/.." && pwd)
json=$root/examples/scenes/json
out=$(mktemp -d /tmp/betelgeuse-command.XXXXXX)
trap 'rm -rf "$out"' EXIT
failed=0
checks=0

fail() {
	echo "check-command: FAILED: $*" >&2
	failed=1
	exit 1
}

# expect CODE DESCRIPTION -- COMMAND...: runs it, keeps stderr in $out/err, checks the exit code.
expect() {
	code=$1
	shift
	what=$1
	shift
	"$@" >"$out/stdout" 2>"$out/err"
	got=$?
	checks=$((checks + 1))
	[ "$got" = "$code" ] || fail "$what: exit $got, want $code; stderr: $(cat "$out/err")"
}

# said TEXT DESCRIPTION: the last command's stderr holds TEXT.
said() {
	grep -qF -- "$1" "$out/err" || fail "$2: stderr lacks '$1': $(cat "$out/err")"
}

echo "== check-command: $cli"
expect 0 "--help" "$cli" --help
for option in -o --size --samples --renderer --backend --crop --tile --max-depth --linear --float --quiet assemble info; do
	grep -qF -- "$option" "$out/stdout" || fail "--help does not mention $option"
done
expect 0 "--version" "$cli" --version
grep -q '^betelgeuse [0-9]' "$out/stdout" || fail "--version prints '$(cat "$out/stdout")'"

# A shipped scene on both renderers, and a model file given directly.
for renderer in cpu gpu; do
	expect 0 "render paper_earth ($renderer)" "$cli" render "$json/paper_earth.json" --size 64x48 --renderer $renderer \
		-o "$out/earth_$renderer.png" --quiet
	[ -s "$out/earth_$renderer.png" ] || fail "render ($renderer) wrote no image"
	# Mesa itself notes the forced GLSL 1.10 of the test environment on stderr; nothing else may be there.
	grep -v -e 'Invalid GLSL version' -e 'gitlab.freedesktop.org/mesa' "$out/err" >"$out/err.own"
	[ -s "$out/err.own" ] && fail "render --quiet ($renderer) printed: $(cat "$out/err.own")"
done
expect 0 "render an OBJ model" "$cli" render "$root/tests/data/two_boxes.obj" --size 48x36 -o "$out/obj.png" \
	--renderer cpu --float "$out/obj.pfm"
head -c 2 "$out/obj.pfm" | grep -q PF || fail "--float wrote no PFM"

# Tiles and crop windows are the full render's pixels: assembled they are the same file.
for renderer in cpu gpu; do
	full=$out/full_$renderer.png
	expect 0 "full render ($renderer)" "$cli" render "$json/glass.json" --size 60x45 --samples 2 --renderer $renderer \
		-o "$full" --quiet
	for i in 1 2 3; do
		expect 0 "tile $i/3 ($renderer)" "$cli" render "$json/glass.json" --size 60x45 --samples 2 \
			--renderer $renderer --tile $i/3 -o "$out/t${i}_$renderer.png" --quiet
	done
	expect 0 "assemble tiles ($renderer)" "$cli" assemble "$out/t1_$renderer.png" "$out/t2_$renderer.png" \
		"$out/t3_$renderer.png" -o "$out/tiled_$renderer.png"
	cmp -s "$full" "$out/tiled_$renderer.png" || fail "3 tiles ($renderer) assembled differ from the full render"
	expect 0 "crop left ($renderer)" "$cli" render "$json/glass.json" --size 60x45 --samples 2 --renderer $renderer \
		--crop 0,0,23,45 -o "$out/left_$renderer.png" --quiet
	expect 0 "crop right ($renderer)" "$cli" render "$json/glass.json" --size 60x45 --samples 2 --renderer $renderer \
		--crop 23,0,60,45 -o "$out/right_$renderer.png" --quiet
	expect 0 "assemble crops ($renderer)" "$cli" assemble "$out/left_$renderer.png" "$out/right_$renderer.png" \
		-o "$out/cropped_$renderer.png"
	cmp -s "$full" "$out/cropped_$renderer.png" || fail "2 crop windows ($renderer) assembled differ from the full render"
done
expect 2 "assemble with a gap" "$cli" assemble "$out/t1_cpu.png" "$out/t3_cpu.png" -o "$out/gap.png"
said "is in no tile" "assemble with a gap"
[ -e "$out/gap.png" ] && fail "assemble with a gap wrote a file"
expect 2 "assemble with an overlap" "$cli" assemble "$out/t1_cpu.png" "$out/t1_cpu.png" -o "$out/overlap.png"
said "in another tile too" "assemble with an overlap"

# Bad usage and bad files: exit 2, a message that names what is wrong, nothing written.
expect 2 "no arguments" "$cli"
expect 2 "unknown command" "$cli" paint "$json/glass.json"
said "unknown command" "unknown command"
expect 2 "missing -o" "$cli" render "$json/glass.json"
said "-o OUT.png is required" "missing -o"
expect 2 "bad --size" "$cli" render "$json/glass.json" --size 0x10 -o "$out/x.png"
said "--size" "bad --size"
expect 2 "bad --tile" "$cli" render "$json/glass.json" --tile 5/4 -o "$out/x.png"
said "--tile" "bad --tile"
expect 2 "--crop beyond the frame" "$cli" render "$json/glass.json" --size 64x48 --crop 0,0,65,10 -o "$out/x.png"
said "beyond the 64x48 frame" "--crop beyond the frame"
expect 2 "bad --renderer" "$cli" render "$json/glass.json" --renderer tpu -o "$out/x.png"
said "neither gpu nor cpu" "bad --renderer"
expect 2 "unknown option" "$cli" render "$json/glass.json" --fast -o "$out/x.png"
said "unknown option --fast" "unknown option"
expect 2 "missing scene file" "$cli" render "$out/none.json" -o "$out/x.png"
said "none.json" "missing scene file"
printf '{"objects": [{"sphere": {"center": [0, 0, 0], "radius": -1}}]}' >"$out/bad.json"
expect 2 "bad radius" "$cli" render "$out/bad.json" -o "$out/x.png"
said "objects[0].sphere.radius" "bad radius"
printf '{"objects": [' >"$out/broken.json"
expect 2 "broken JSON" "$cli" render "$out/broken.json" -o "$out/x.png"
said "broken.json" "broken JSON"
printf '{"camera": {"fov": 40}}' >"$out/unknown.json"
expect 2 "unknown key" "$cli" render "$out/unknown.json" -o "$out/x.png"
said "camera.fov" "unknown key"
[ -e "$out/x.png" ] && fail "a refused render wrote $out/x.png"
expect 1 "unwritable output" "$cli" render "$json/glass.json" --size 8x8 --renderer cpu -o "$out/no/such/dir/x.png"
said "no/such/dir/x.png" "unwritable output"

# info: the counts, the bounds and the plan.
expect 0 "info" "$cli" info "$json/bunny.json"
for word in objects triangles lights bounds camera "GPU plan"; do
	grep -qF "$word" "$out/stdout" || fail "info prints no '$word': $(cat "$out/stdout")"
done
grep -q "3674 triangles" "$out/stdout" || fail "info: the bunny's 3674 triangles are not counted: $(cat "$out/stdout")"

[ "$failed" = 0 ] && echo "check-command: $checks commands as expected"
