#!/bin/sh
# Holds the libraries to their headers. A shared library must export exactly the functions its
# header marks public (MACS_API, BG_API), nothing more and nothing less; a static archive may hold
# internal symbols too, but each one must carry the library's internal prefix (macsi_, bgi_), so
# that a program can define any name outside the four reserved prefixes without replacing or
# colliding with the library's own (a user's gpu_release_all once did both).
# Usage: check_symbols.sh BUILD_DIR
build=$1
failed=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# lib header api public-prefix internal-prefix
check() {
	lib=$1 header=$2 api=$3 pub=$4 internal=$5
	sed -n "s/^$api .*\b\($pub[a-z0-9_]*\)(.*/\1/p" "$header" | sort -u >"$work/public"
	if [ ! -s "$work/public" ]; then
		echo "FAIL $header: no function marked $api"
		failed=1
		return
	fi
	# AddressSanitizer adds an ODR indicator beside every global (__odr_asan.<name>, or __asan_*):
	# the compiler's names, not the library's, so they are left out.
	nm -D --defined-only "$build/lib$lib.so" | awk 'NF == 3 {print $3}' | grep -v '^__odr_asan\.\|^__asan_' |
		sort -u >"$work/exported"
	if ! diff "$work/public" "$work/exported" >"$work/diff"; then
		echo "FAIL lib$lib.so exports other than $header marks ('>' exported but not public, '<' public but not exported):"
		grep '^[<>]' "$work/diff" | sed 's/^/    /'
		failed=1
	fi
	nm -g --defined-only "$build/lib$lib.a" | awk 'NF == 3 {print $3}' | grep -v '^__odr_asan\.\|^__asan_' |
		sort -u >"$work/archive"
	grep -v "^$pub" "$work/archive" | grep -v "^$internal" >"$work/unprefixed"
	if [ -s "$work/unprefixed" ]; then
		echo "FAIL lib$lib.a holds symbols outside $pub and $internal:"
		sed 's/^/    /' "$work/unprefixed"
		failed=1
	fi
	grep "^$pub" "$work/archive" | grep -v "^$internal" >"$work/archive_public"
	if ! diff "$work/public" "$work/archive_public" >"$work/diff"; then
		echo "FAIL lib$lib.a: $pub names that $header does not declare public ('>') or lacks ('<'); internal names take $internal:"
		grep '^[<>]' "$work/diff" | sed 's/^/    /'
		failed=1
	fi
	echo "lib$lib: $(wc -l <"$work/public") public functions exported, $(grep -c "^$internal" "$work/archive") internal symbols, all prefixed $internal"
}

check macs include/macs.h MACS_API macs_ macsi_
check betelgeuse include/betelgeuse.h BG_API bg_ bgi_
check betelgeuse_scenefile include/betelgeuse_scenefile.h BG_API bg_scenefile_ bgi_sf_

# GL, EGL and OSMesa are loaded at run time (docs/architecture.md, "Headless contexts"), so that the
# libraries and the command start where Mesa ships no OSMesa: none of them may name one as needed.
for f in "$build/libmacs.so" "$build/libbetelgeuse.so" "$build/libbetelgeuse_scenefile.so" "$build/betelgeuse"; do
	gl=$(readelf -d "$f" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | grep -E '^lib(GL|GLX|EGL|OpenGL|OSMesa)[.-]')
	if [ -n "$gl" ]; then
		echo "FAIL $(basename "$f") links to $(echo $gl): the window-system libraries are loaded at run time"
		failed=1
	else
		echo "$(basename "$f"): links no GL, EGL or OSMesa library"
	fi
done

# GLFW is the viewer's (the command's): a program that links the libraries must not get it with them.
for f in "$build/libmacs.so" "$build/libbetelgeuse.so" "$build/libbetelgeuse_scenefile.so" "$build/libmacs.a" \
	"$build/libbetelgeuse.a" "$build/libbetelgeuse_scenefile.a" "$build/macs.pc" "$build/betelgeuse.pc" \
	"$build/betelgeuse_scenefile.pc"; do
	case $f in
	*.so) found=$(readelf -d "$f" | grep -i 'NEEDED.*glfw') ;;
	*.a) found=$(nm -u "$f" 2>/dev/null | grep -i ' glfw') ;;
	*) found=$(grep -i glfw "$f") ;;
	esac
	if [ -n "$found" ]; then
		echo "FAIL $(basename "$f") names GLFW ($found): only the betelgeuse command may link it"
		failed=1
	fi
done
echo "libraries and pkg-config files: no GLFW"
exit $failed
