#!/bin/sh
# Validates every glsl110/ file as GLSL 1.10 with glslangValidator. .vert/.frag files are whole
# shaders; a .glsl library file is checked as fragment code after the files its "// requires:" line
# names (recursively, each once, without their #version lines), followed by an empty main.
# Usage: glsl_check.sh <glsl110 dir>
dir=$1
command -v glslangValidator >/dev/null || { echo "glslangValidator missing (apt-get install glslang-tools)"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Prints the bodies (line 1 dropped) of a file's requirements, then of the file itself.
emit() {
	case " $seen " in *" $1 "*) return 0 ;; esac
	seen="$seen $1"
	[ -f "$dir/$1" ] || { echo "missing required file $1" >&2; return 1; }
	for req in $(sed -n '2s|^// requires:||p' "$dir/$1"); do
		emit "$req" || return 1
	done
	tail -n +2 "$dir/$1"
}

fail=0
for f in "$dir"/*; do
	name=$(basename "$f")
	head -n1 "$f" | grep -q '^#version 110$' || { echo "FAIL $name: line 1 is not #version 110"; fail=1; continue; }
	case $name in
	*.vert) glslangValidator -S vert "$f" >"$tmp/log" 2>&1 ;;
	*.frag) glslangValidator -S frag "$f" >"$tmp/log" 2>&1 ;;
	*)
		seen=""
		{ echo '#version 110'; emit "$name" && echo 'void main() {}'; } >"$tmp/src.frag" 2>"$tmp/log" &&
			glslangValidator -S frag "$tmp/src.frag" >>"$tmp/log" 2>&1
		;;
	esac || { echo "FAIL $name"; cat "$tmp/log"; fail=1; }
done
[ $fail = 0 ] && echo "glsl110: every shader passes glslangValidator as version 110"
exit $fail
