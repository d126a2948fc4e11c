#!/bin/sh
# make check-command: the `betelgeuse` command end to end (docs/command.md). Every check prints what
# it ran; the first failure stops the script with exit 1.
#   usage: tests/check_command.sh BUILD/betelgeuse
set -u
cli=$1
# Absolute, so that checks may run it from another folder.
case $cli in /*) ;; *) cli=$PWD/$cli ;; esac
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
# A scene that reads no other file, for checks that copy it around.
printf '{"objects": [{"sphere": {"center": [0, 0, -3], "radius": 1}}]}' >"$out/sphere.json"
expect 0 "--help" "$cli" --help
for option in -o --size --samples --renderer --backend --crop --tile --max-depth --integrator --linear --float --quiet --strict --timings assemble info \
	--up --smooth --camera --look-from --look-at --fov --aperture --focus-distance; do
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
# The shipped scenes of the area lights, the lens, glossy reflection and the environment, small, on the GPU
# (test_scenefile_lights and test_scenefile_environment hold the CPU to builders and the GPU to the CPU;
# the multipass draws no environment, so the GPU plan is the automatic one).
for scene in area_lights depth_of_field glossy environment; do
	expect 0 "render $scene" "$cli" render "$json/$scene.json" --size 64x48 -o "$out/$scene.png" --quiet
	[ -s "$out/$scene.png" ] || fail "render $scene wrote no image"
done
# The path integrator's shipped scene, on the CPU (test_scenefile_environment checks its light).
expect 0 "render window_room (cpu)" "$cli" render "$json/window_room.json" --size 32x24 --samples 2 --renderer cpu \
	-o "$out/window_room.png" --quiet
[ -s "$out/window_room.png" ] || fail "render window_room wrote no image"
expect 0 "render an OBJ model" "$cli" render "$root/tests/data/two_boxes.obj" --size 48x36 -o "$out/obj.png" \
	--renderer cpu --float "$out/obj.pfm"
head -c 2 "$out/obj.pfm" | grep -q PF || fail "--float wrote no PFM"
# What a model loses is said on stderr, terminal or not (here a file), and --quiet silences it.
expect 0 "a model warning without a terminal" "$cli" render "$root/tests/data/emissive_webp_texture.gltf" --size 32x24 \
	--renderer cpu -o "$out/warn.png"
said "warning: " "a model warning without a terminal"
said "glow_not_read.webp" "a model warning without a terminal"
expect 0 "a model warning under --quiet" "$cli" render "$root/tests/data/emissive_webp_texture.gltf" --size 32x24 \
	--renderer cpu -o "$out/warn.png" --quiet
grep -q "warning: " "$out/err" && fail "--quiet printed a warning: $(cat "$out/err")"
# --strict makes any warning fatal (exit 2) in render and info, and writes no image.
rm -f "$out/strict.png"
expect 2 "a model warning under --strict" "$cli" render "$root/tests/data/emissive_webp_texture.gltf" --size 32x24 \
	--renderer cpu -o "$out/strict.png" --strict
said "2 warnings while loading, fatal under --strict" "a model warning under --strict"
[ -e "$out/strict.png" ] && fail "render --strict wrote an image after a fatal warning"
expect 2 "info under --strict" "$cli" info "$root/tests/data/emissive_webp_texture.gltf" --strict
expect 0 "a clean scene under --strict" "$cli" info "$json/glass.json" --strict
# --timings names every phase, and the frame rendered again compiles nothing new.
expect 0 "--timings" "$cli" render "$json/glass.json" --size 48x36 -o "$out/timed.png" --quiet --timings
for phase in "scene load" "context" "programs compiled" "render again" "PNG encode and write" "put in place"; do
	said "$phase" "--timings"
done

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
# A render the GPU renderer tiles itself (1600x1400 at 4 samples is beyond its default 1 GiB budget of
# render targets: 2 tiles) writes its PNG as the tiles' rows come: the same file as two --tile renders,
# each of one piece, assembled.
expect 0 "full render in tiles (gpu)" "$cli" render "$json/paper_earth.json" --size 1600x1400 --samples 4 \
	-o "$out/streamed.png" --quiet
for i in 1 2; do
	expect 0 "tile $i/2 of the tiled render" "$cli" render "$json/paper_earth.json" --size 1600x1400 --samples 4 \
		--tile $i/2 -o "$out/s${i}.png" --quiet
done
expect 0 "assemble the two tiles" "$cli" assemble "$out/s1.png" "$out/s2.png" -o "$out/unstreamed.png"
cmp -s "$out/streamed.png" "$out/unstreamed.png" || fail "a PNG streamed from tiles differs from its tiles assembled"
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

# Limits are the library's (BG_MAX_IMAGE_SIDE, BG_MAX_SAMPLES, BG_MAX_DEPTH in betelgeuse.h), and every
# number is parsed with overflow checks: a value the parser takes is one the renderer takes.
for bad in "--size 20000x20000" "--size 16385x1" "--samples 257" "--max-depth 65" "--tile 1/4294967297"; do
	option=${bad%% *}
	expect 2 "$bad" "$cli" render "$json/glass.json" $bad -o "$out/x.png"
	said "$option" "$bad"
done
expect 0 "--size at the largest side" "$cli" render "$out/sphere.json" --size 16384x2 --crop 0,0,4,2 --renderer cpu \
	-o "$out/x.png"
rm -f "$out/x.png"
# 4294967312 is 2^32 + 16: read with sscanf's %d it wrapped to 16, inside the 32x32 frame, and rendered.
for crop in 0,0,4294967312,4294967312 -1,0,4,4 0,0,4,4x 0,,4,4 0,0,4 0,0,4,4, " 0,0,4,4" 0,0,16385,4 ""; do
	expect 2 "--crop '$crop'" "$cli" render "$out/sphere.json" --size 32x32 --renderer cpu --crop "$crop" -o "$out/x.png"
	said "--crop" "--crop '$crop'"
done
[ -e "$out/x.png" ] && fail "a refused --size, --samples, --max-depth, --tile or --crop wrote $out/x.png"

# --integrator overrides the scene file's settings.integrator both ways: a file that asks for path renders
# as --integrator path on a file without it (the same bytes: the samples are the same), and
# --integrator whitted undoes it. The CPU draws path; the GPU either draws it or refuses it (exit 1)
# naming the integrator and --renderer cpu, writing nothing.
lit='"lights": [{"position": [3, 6, 4]}], "objects": [{"sphere": {"center": [0, 0, -3], "radius": 1}},
	{"plane": {"point": [0, -1, 0], "normal": [0, 1, 0]}}]'
printf '{%s}' "$lit" >"$out/lit.json"
printf '{"settings": {"integrator": "path"}, %s}' "$lit" >"$out/lit_path.json"
for scene in lit lit_path; do
	for integrator in whitted path; do
		expect 0 "render $scene --integrator $integrator (cpu)" "$cli" render "$out/$scene.json" --size 32x24 \
			--samples 2 --renderer cpu --integrator $integrator -o "$out/${scene}_$integrator.png" --quiet
	done
done
expect 0 "render lit_path (cpu)" "$cli" render "$out/lit_path.json" --size 32x24 --samples 2 --renderer cpu \
	-o "$out/lit_path_file.png" --quiet
cmp -s "$out/lit_path_file.png" "$out/lit_path.png" || fail "a file's \"integrator\": \"path\" differs from --integrator path"
cmp -s "$out/lit_path_file.png" "$out/lit_whitted.png" && fail "\"integrator\": \"path\" rendered Whitted's image"
cmp -s "$out/lit_path_whitted.png" "$out/lit_whitted.png" || fail "--integrator whitted did not undo the file's path"
# The GPU: exit 0 once a plan draws path, until then exit 1 with the refusal; never anything else.
checks=$((checks + 1))
rm -f "$out/gpu_path.png"
"$cli" render "$out/lit.json" --size 32x24 --integrator path -o "$out/gpu_path.png" --quiet >"$out/stdout" 2>"$out/err"
got=$?
if [ "$got" = 1 ]; then
	said "BG_INTEGRATOR_PATH" "render --integrator path (gpu)"
	said "--renderer cpu" "render --integrator path (gpu)"
	[ -e "$out/gpu_path.png" ] && fail "a refused GPU render of path wrote an image"
elif [ "$got" != 0 ]; then
	fail "render --integrator path (gpu): exit $got, want 0 or 1; stderr: $(cat "$out/err")"
fi
expect 2 "--integrator bidirectional" "$cli" render "$out/lit.json" --integrator bidirectional -o "$out/x.png"
said "--integrator: 'bidirectional' is neither whitted nor path" "--integrator bidirectional"
expect 2 "--integrator without a value" "$cli" render "$out/lit.json" --integrator
said "--integrator needs a value" "--integrator without a value"
printf '{"settings": {"integrator": "photon"}}' >"$out/bad_integrator.json"
expect 2 "a file's unknown integrator" "$cli" render "$out/bad_integrator.json" --renderer cpu -o "$out/x.png"
said "settings.integrator: \"photon\" is not one of \"whitted\", \"path\"" "a file's unknown integrator"
expect 0 "info of a path scene" "$cli" info "$out/lit_path.json" --renderer cpu
grep -qF "integrator path" "$out/stdout" || fail "info of a path scene: $(cat "$out/stdout")"
expect 0 "info --integrator whitted" "$cli" info "$out/lit_path.json" --renderer cpu --integrator=whitted
grep -qF "integrator whitted" "$out/stdout" || fail "info --integrator whitted: $(cat "$out/stdout")"
[ -e "$out/x.png" ] && fail "a refused --integrator wrote $out/x.png"

# An output that names an input is refused (exit 2, naming the option and the input) and the input is
# left as it was, however the path spells it: the same name, ./, .., a symbolic or a hard link.
w=$out/inputs
mkdir "$w" "$w/sub"
cp "$out/sphere.json" "$w/s.json"
ln -s s.json "$w/link.json"
ln "$w/s.json" "$w/hard.json"
for o in "$w/s.json" "$w/./s.json" "$w/sub/../s.json" "$w/link.json" "$w/hard.json"; do
	cp "$out/sphere.json" "$w/s.json"
	expect 2 "-o $o (the scene)" "$cli" render "$w/s.json" --size 8x8 --renderer cpu -o "$o"
	said "-o $o" "-o $o (the scene)"
	said "input file $w/s.json" "-o $o (the scene)"
	cmp -s "$w/s.json" "$out/sphere.json" || fail "-o $o overwrote the scene file"
done
cp "$out/sphere.json" "$w/s.json"
expect 2 "-o ./s.json, relative" sh -c 'cd "$1" && exec "$2" render s.json --size 8x8 --renderer cpu -o ./s.json' \
	sh "$w" "$cli"
said "-o ./s.json" "-o ./s.json, relative"
cmp -s "$w/s.json" "$out/sphere.json" || fail "-o ./s.json overwrote the scene file"
cp "$out/sphere.json" "$w/s.json"
expect 2 "--float naming the scene" "$cli" render "$w/s.json" --size 8x8 --renderer cpu -o "$w/o.png" \
	--float "$w/s.json"
said "--float $w/s.json" "--float naming the scene"
cmp -s "$w/s.json" "$out/sphere.json" || fail "--float overwrote the scene file"
cp "$out/sphere.json" "$w/s.json"
expect 2 "-o and --float naming one file" "$cli" render "$w/s.json" --size 8x8 --renderer cpu -o "$w/o.png" \
	--float "$w/sub/../o.png"
said "--float" "-o and --float naming one file"
[ -e "$w/o.png" ] && fail "-o and --float naming one file wrote it"
cp "$out/t2_cpu.png" "$out/t2_copy.png"
expect 2 "assemble -o naming a tile" "$cli" assemble "$out/t1_cpu.png" "$out/t2_cpu.png" "$out/t3_cpu.png" \
	-o "$out/./t2_cpu.png"
said "-o $out/./t2_cpu.png" "assemble -o naming a tile"
cmp -s "$out/t2_cpu.png" "$out/t2_copy.png" || fail "assemble -o overwrote a tile"

# no_temps DIR: no temporary output (.NAME.XXXXXX) is left in DIR.
no_temps() {
	for f in "$1"/.[!.]*; do
		[ -e "$f" ] && fail "a temporary file is left behind: $f"
	done
	return 0
}

# Outputs go to a temporary beside the target and are renamed into place once every output is written:
# a failed write leaves the existing file as it was and no temporary behind.
w=$out/atomic
mkdir "$w"
printf 'an image from before\n' >"$w/o.png"
cp "$w/o.png" "$out/o.before"
expect 1 "--float into a missing folder" "$cli" render "$out/sphere.json" --size 8x8 --renderer cpu -o "$w/o.png" \
	--float "$w/missing/x.pfm"
said "missing/x.pfm" "--float into a missing folder"
cmp -s "$w/o.png" "$out/o.before" || fail "--float into a missing folder changed the existing PNG"
no_temps "$w"
# A file-size limit of 1 KiB (2 blocks of 512 bytes) the PNG (some 3 KB) cannot fit in; SIGXFSZ is ignored
# so that the write fails with EFBIG instead of killing the process.
checks=$((checks + 1))
(trap '' XFSZ && ulimit -f 2 && exec "$cli" render "$out/sphere.json" --size 512x512 --renderer cpu --quiet \
	-o "$w/o.png") >"$out/stdout" 2>"$out/err"
got=$?
[ "$got" = 1 ] || fail "a write beyond ulimit -f: exit $got, want 1; stderr: $(cat "$out/err")"
said "o.png" "a write beyond ulimit -f"
cmp -s "$w/o.png" "$out/o.before" || fail "a write beyond ulimit -f changed or removed the existing PNG"
no_temps "$w"
# The same limit with a PNG that fits (a few hundred bytes) and a PFM that does not (48 KiB): the PNG,
# written first, must not replace the old one either.
checks=$((checks + 1))
(trap '' XFSZ && ulimit -f 2 && exec "$cli" render "$out/sphere.json" --size 64x64 --renderer cpu --quiet \
	-o "$w/o.png" --float "$w/o.pfm") >"$out/stdout" 2>"$out/err"
got=$?
[ "$got" = 1 ] || fail "a PFM beyond ulimit -f: exit $got, want 1; stderr: $(cat "$out/err")"
said "o.pfm" "a PFM beyond ulimit -f"
cmp -s "$w/o.png" "$out/o.before" || fail "a PFM beyond ulimit -f changed or removed the existing PNG"
[ -e "$w/o.pfm" ] && fail "a PFM beyond ulimit -f left $w/o.pfm"
no_temps "$w"
# A successful run: both files in place, with the permissions a plain create gives under the umask.
for mask in 022 027; do
	expect 0 "render under umask $mask" sh -c 'umask $1 && shift && exec "$@"' sh $mask "$cli" render \
		"$out/sphere.json" --size 8x8 --renderer cpu -o "$w/o.png" --float "$w/o.pfm"
	want=-rw-r--r--
	[ $mask = 027 ] && want=-rw-r-----
	for f in "$w/o.png" "$w/o.pfm"; do
		mode=$(ls -l "$f" | cut -c1-10)
		[ "$mode" = "$want" ] || fail "$f under umask $mask: mode $mode, want $want"
	done
	rm "$w/o.png" "$w/o.pfm"
done
# A replaced output keeps its own mode: a private render stays private.
printf 'private\n' >"$w/o.png"
chmod 600 "$w/o.png"
expect 0 "render over a 0600 PNG" "$cli" render "$out/sphere.json" --size 8x8 --renderer cpu -o "$w/o.png"
mode=$(ls -l "$w/o.png" | cut -c1-10)
[ "$mode" = -rw------- ] || fail "render over a 0600 PNG left mode $mode, want -rw-------"
rm "$w/o.png"
# An output that is a symbolic link stays one: the file it points to is replaced (or made).
ln -s real.png "$w/link.png"
expect 0 "render through a link" "$cli" render "$out/sphere.json" --size 8x8 --renderer cpu -o "$w/link.png"
[ -L "$w/link.png" ] || fail "render through a link replaced the link"
head -c 4 "$w/real.png" | grep -q PNG || fail "render through a link did not write the file it points to"
rm "$w/link.png" "$w/real.png"
printf 'an image from before\n' >"$w/o.png"
expect 0 "render over an existing PNG" "$cli" render "$out/sphere.json" --size 8x8 --renderer cpu -o "$w/o.png"
head -c 4 "$w/o.png" | grep -q PNG || fail "render over an existing PNG did not replace it"
no_temps "$w"

# A forged tile whose Betelgeuse-Tile chunk claims a 100000x100000 frame (a 1x1 PNG with a tEXt chunk,
# "0 0 100000 100000"), and one whose frame width, 2^32 + 1, wrapped to 1 with sscanf: malformed tiles.
# forged_tile FILE CHUNK: a 1x1 PNG around CHUNK, the tEXt chunk given as printf escapes.
forged_tile() {
	{
		printf '\211PNG\015\012\032\012\000\000\000\015IHDR\000\000\000\001\000\000\000\001\010\006\000\000\000'
		printf '\037\025\304\211'
		printf "$2"
		printf '\000\000\000\015IDATx\234c\370\317\300\360\037\000\005\000\001\377\211\231=\035'
		printf '\000\000\000\000IEND\256B`\202'
	} >"$1"
}
forged_tile "$out/huge_tile.png" '\000\000\000!tEXtBetelgeuse-Tile\0000 0 100000 100000\215\261;\214'
forged_tile "$out/wrapped_tile.png" '\000\000\000 tEXtBetelgeuse-Tile\0000 0 4294967297 1\267\004\2404'
for tile in huge_tile wrapped_tile; do
	expect 2 "assemble $tile" "$cli" assemble "$out/$tile.png" -o "$out/x.png"
	said "$tile.png: malformed Betelgeuse-Tile" "assemble $tile"
done
# Tiles that are not regular files: named, and a FIFO does not block the open (timeout: a hang fails).
mkfifo "$out/fifo.png"
mkdir "$out/dir.png"
expect 2 "assemble a FIFO tile" timeout 20 "$cli" assemble "$out/fifo.png" -o "$out/x.png"
said "fifo.png: is not a regular file (a FIFO)" "assemble a FIFO tile"
expect 2 "assemble a directory tile" timeout 20 "$cli" assemble "$out/dir.png" -o "$out/x.png"
said "dir.png: is a directory" "assemble a directory tile"
[ -e "$out/x.png" ] && fail "a refused assemble wrote $out/x.png"

# info: the counts, the bounds and the plan.
expect 0 "info" "$cli" info "$json/bunny.json"
for word in objects triangles lights bounds camera "GPU plan"; do
	grep -qF "$word" "$out/stdout" || fail "info prints no '$word': $(cat "$out/stdout")"
done
grep -q "3674 triangles" "$out/stdout" || fail "info: the bunny's 3674 triangles are not counted: $(cat "$out/stdout")"

# The model options (docs/command.md, "Model options"): what they change, read back through info's
# bounds and camera lines and the rendered files, and each bad value refused naming its option.
data=$root/tests/data
said_out() {
	grep -qF -- "$1" "$out/stdout" || fail "$2: stdout lacks '$1': $(cat "$out/stdout")"
}
expect 0 "info, a Z-up model as its file has it" "$cli" info "$data/zup_tower.obj" --renderer cpu
said_out "bounds     (-0.5, -0.5, 0) .. (0.5, 0.5, 3)" "a Z-up model as its file has it"
expect 0 "info --up z" "$cli" info "$data/zup_tower.obj" --renderer cpu --up z
said_out "bounds     (-0.5, 0, -0.5) .. (0.5, 3, 0.5)" "--up z"
said_out "looking at (0, 1.5, 0)" "--up z: the framing camera looks at the standing tower's middle"
expect 0 "info --up=-z" "$cli" info "$data/zup_tower.obj" --renderer cpu --up=-z
said_out "bounds     (-0.5, -3, -0.5) .. (0.5, 0, 0.5)" "--up=-z"
expect 0 "render --up z" "$cli" render "$data/zup_tower.obj" --up z --size 32x32 --renderer cpu -o "$out/up_z.png" -q
expect 0 "render without --up" "$cli" render "$data/zup_tower.obj" --size 32x32 --renderer cpu -o "$out/up_y.png" -q
cmp -s "$out/up_z.png" "$out/up_y.png" && fail "--up z rendered the same image as the file's own axes"
expect 2 "--up x" "$cli" render "$data/zup_tower.obj" --up x -o "$out/x.png"
said "--up: 'x' is not an axis" "--up x"

# --smooth shades a faceted ball: another image; its angle is optional and read only when a number.
expect 0 "render a faceted ball" "$cli" render "$data/ico_no_normals.ply" --size 32x32 --renderer cpu \
	-o "$out/facets.png" -q
expect 0 "render --smooth before the scene" "$cli" render --smooth "$data/ico_no_normals.ply" --size 32x32 \
	--renderer cpu -o "$out/smooth.png" -q
cmp -s "$out/facets.png" "$out/smooth.png" && fail "--smooth rendered the faceted ball unchanged"
expect 0 "render --smooth 180" "$cli" render "$data/ico_no_normals.ply" --smooth 180 --size 32x32 --renderer cpu \
	-o "$out/smooth180.png" -q
cmp -s "$out/smooth.png" "$out/smooth180.png" || fail "--smooth alone is not --smooth 180"
expect 0 "render --smooth=0" "$cli" render "$data/ico_no_normals.ply" --smooth=0 --size 32x32 --renderer cpu \
	-o "$out/smooth0.png" -q
cmp -s "$out/smooth0.png" "$out/smooth.png" && fail "--smooth=0 smoothed the ball"
expect 2 "--smooth 200" "$cli" render "$data/ico_no_normals.ply" --smooth 200 -o "$out/x.png"
said "--smooth: '200' is not a crease angle" "--smooth 200"
expect 2 "--smooth=x" "$cli" render "$data/ico_no_normals.ply" --smooth=x -o "$out/x.png"
said "--smooth: 'x'" "--smooth=x"

# --camera: the file's cameras from 1, auto for the framing one; out of range names the count.
expect 0 "info, two cameras" "$cli" info "$data/two_cameras.gltf" --renderer cpu
said_out "camera     (0.3, 0.3, 4)" "info, two cameras"
said_out "the file's camera 1 of 2" "info, two cameras"
expect 0 "info --camera 2" "$cli" info "$data/two_cameras.gltf" --camera 2 --renderer cpu
said_out "camera     (4, 0.3, 0.3) looking at (3, 0.3, 0.3)" "--camera 2"
said_out "the file's camera 2 of 2" "--camera 2"
expect 0 "info --camera auto" "$cli" info "$data/two_cameras.gltf" --camera auto --renderer cpu
said_out "looking at (0.5, 0.5, 0.5)" "--camera auto"
said_out "framing the bounds; the file has 2 cameras: --camera 1 .. 2" "--camera auto"
expect 2 "--camera 3" "$cli" render "$data/two_cameras.gltf" --camera 3 --renderer cpu -o "$out/x.png"
said "--camera: camera 3 asked for, but the file has 2 cameras" "--camera 3"
expect 2 "--camera 0" "$cli" info "$data/two_cameras.gltf" --camera 0
said "--camera: '0'" "--camera 0"
expect 2 "--camera 1 of a file without one" "$cli" info "$data/tetra.ply" --camera 1 --renderer cpu
said "--camera: camera 1 asked for, but the file has no camera" "--camera 1 of a file without one"

# --look-from, --look-at, --fov: each replaces its part of the chosen camera, of a JSON scene's too.
expect 0 "info --look-from --fov" "$cli" info "$data/two_cameras.gltf" --look-from 1,2,3 --fov 30 --renderer cpu
said_out "camera     (1, 2, 3) looking at (0.3, 0.3, 3), fov_y 30 degrees" "--look-from --fov"
expect 0 "info --look-at of a JSON scene" "$cli" info "$out/sphere.json" --look-at=0,0,-3 --look-from 0,1,2 \
	--renderer cpu
said_out "camera     (0, 1, 2) looking at (0, 0, -3)" "--look-at of a JSON scene"
expect 0 "render --look-from --look-at" "$cli" render "$data/two_cameras.gltf" --look-from 3,3,3 --look-at 0,0,0 \
	--size 32x32 --renderer cpu -o "$out/look.png" -q
expect 0 "render with the file's camera" "$cli" render "$data/two_cameras.gltf" --size 32x32 --renderer cpu \
	-o "$out/file_camera.png" -q
cmp -s "$out/look.png" "$out/file_camera.png" && fail "--look-from and --look-at rendered the file camera's image"
expect 2 "--look-from equal to --look-at" "$cli" render "$data/two_cameras.gltf" --look-from 1,1,1 --look-at 1,1,1 \
	-o "$out/x.png"
said "--look-from 1,1,1: the same point as --look-at" "--look-from equal to --look-at"
printf '{"camera": {"position": [0, 0, 5], "look_at": [0, 0, -3]}, "objects": [{"sphere": {}}]}' >"$out/cam.json"
expect 2 "--look-from at the file camera's point" "$cli" info "$out/cam.json" --look-from 0,0,-3 --renderer cpu
said "--look-from: the camera at (0, 0, -3) would look at its own position" "--look-from at the file camera's point"
expect 2 "--look-from straight above" "$cli" info "$data/tetra.ply" --look-from 0.25,9,0.25 --look-at 0.25,0,0.25 \
	--renderer cpu
said "along the camera's up" "--look-from straight above"
expect 2 "--look-from with two numbers" "$cli" render "$data/two_cameras.gltf" --look-from 1,2 -o "$out/x.png"
said "--look-from: '1,2' is not a point X,Y,Z" "--look-from with two numbers"
expect 2 "--look-at with a stray character" "$cli" render "$data/two_cameras.gltf" --look-at 1,2,3x -o "$out/x.png"
said "--look-at: '1,2,3x'" "--look-at with a stray character"
expect 2 "--look-at nan" "$cli" render "$data/two_cameras.gltf" --look-at nan,0,0 -o "$out/x.png"
said "--look-at: 'nan,0,0'" "--look-at nan"
for fov in 0 180 -5 abc 1e999; do
	expect 2 "--fov $fov" "$cli" render "$data/two_cameras.gltf" --fov $fov -o "$out/x.png"
	said "--fov: '$fov' is not a vertical field of view" "--fov $fov"
done
# --aperture and --focus-distance: the chosen camera's lens, a JSON scene's too, 0 a value of each
# (a pinhole; focus at the point looked at); info prints a lens line only for a lens.
printf '{"camera": {"aperture_radius": 0.3, "focus_distance": 4}, "objects": [{"sphere": {}}]}' >"$out/lens.json"
expect 0 "info of a file's lens" "$cli" info "$out/lens.json" --renderer cpu
said_out "lens       aperture radius 0.3, in focus at distance 4" "info of a file's lens"
expect 0 "info --aperture --focus-distance=0" "$cli" info "$out/lens.json" --aperture 0.5 --focus-distance=0 \
	--renderer cpu
said_out "lens       aperture radius 0.5, in focus at the point looked at" "--aperture --focus-distance=0"
said_out "changed by" "--aperture --focus-distance=0"
expect 0 "info --aperture 0" "$cli" info "$out/lens.json" --aperture 0 --renderer cpu
grep -q '^lens' "$out/stdout" && fail "--aperture 0 left a lens: $(cat "$out/stdout")"
expect 0 "render --aperture" "$cli" render "$out/sphere.json" --aperture 0.5 --focus-distance 1 --samples 4 \
	--size 32x32 --renderer cpu -o "$out/lens.png" -q
expect 0 "render a pinhole" "$cli" render "$out/sphere.json" --samples 4 --size 32x32 --renderer cpu \
	-o "$out/pinhole.png" -q
cmp -s "$out/lens.png" "$out/pinhole.png" && fail "--aperture rendered the pinhole's image"
for bad in -0.1 abc 1e999 nan; do
	expect 2 "--aperture $bad" "$cli" render "$out/sphere.json" --aperture $bad -o "$out/x.png"
	said "--aperture: '$bad' is not a lens radius" "--aperture $bad"
done
for bad in -3 1,2; do
	expect 2 "--focus-distance $bad" "$cli" info "$out/sphere.json" --focus-distance $bad
	said "--focus-distance: '$bad' is not a focus distance" "--focus-distance $bad"
done
expect 2 "--aperture without a value" "$cli" info "$out/sphere.json" --aperture
said "--aperture needs a value" "--aperture without a value"
for option in "--up z" "--smooth" "--camera 1"; do
	expect 2 "$option for a JSON scene" "$cli" render "$out/sphere.json" $option -o "$out/x.png"
	said "${option%% *} applies to model files, not to a JSON scene" "$option for a JSON scene"
done

# What the scene-file library tells the command: every file it reads (here a texture) is an input that
# -o may not overwrite, and a scene that is a FIFO or a directory is refused without blocking.
w=$out/textured
mkdir "$w"
cp "$json/paper_earth.json" "$json/earth.png" "$w/"
expect 2 "-o naming the scene's texture" "$cli" render "$w/paper_earth.json" --size 8x8 --renderer cpu -o "$w/earth.png"
said "earth.png" "-o naming the scene's texture"
cmp -s "$w/earth.png" "$json/earth.png" || fail "-o overwrote the scene's texture"
mkfifo "$out/fifo.json"
expect 2 "a FIFO scene" timeout 20 "$cli" render "$out/fifo.json" --renderer cpu -o "$out/x.png"
said "is not a regular file (a FIFO)" "a FIFO scene"
mkdir "$out/dir.json"
expect 2 "a directory scene" timeout 20 "$cli" render "$out/dir.json" --renderer cpu -o "$out/x.png"
said "is a directory" "a directory scene"

[ "$failed" = 0 ] && echo "check-command: $checks commands as expected"
