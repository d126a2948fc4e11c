#!/bin/sh
# Packs what the device check needs on a GPU machine (make device-pack; docs/device_check.md) into
# one folder: run.sh (the one command there), payload.tar.xz and debs/ (glvnd's EGL packages).
# The payload holds, under one root that the runner unpacks anywhere:
#   bin/      every suite, the runner's crash suite, device_info, probe_headless, bench_frame_cost,
#             bench_paper, bench_distribution and the betelgeuse command, without their debug info (PACK_DEBUG=1
#             keeps it, for line numbers in backtraces; their symbols stay either way)
#   lib/      every shared library they load that is not the C library itself (ldd): cmocka, cJSON,
#             assimp and its own, libpng, TurboJPEG, stb, zlib, GLFW and X11's client libraries;
#             lib/fallback/ holds libstdc++ and libgcc_s, used only where the machine's own cannot
#             load the rest (their newest symbols need this machine's C library)
#   tests/run_suites.sh, tests/device/check_runner.sh, tests/data, examples/scenes/json: the runner
#             and the files the suites read, at the paths they read them from
#   suite-times (this machine's last suite times, to start the longest first), manifest.txt
# The suites compile their shaders from strings built in (glsl110/ is embedded), and load GL through
# libEGL.so.1 at run time: no GL library is packed but glvnd's, as .deb files for the runner.
# Usage: pack.sh BUILD_DIR OUT_DIR
set -u
build=$1
dest=$2
case $(uname -m) in
x86_64) ;;
*) echo "device-pack: this machine is $(uname -m); the GPU machines are x86-64: build the pack on x86-64"; exit 1 ;;
esac
for f in "$build/betelgeuse" "$build/tests/device/crash_suite" "$build/tests/device/device_info" \
	"$build/bench/bench_frame_cost" "$build/bench/bench_paper" "$build/bench/bench_distribution"; do
	[ -x "$f" ] || { echo "device-pack: $f is missing (make device-pack builds it)"; exit 1; }
done
mkdir -p "$dest" || exit 1
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
root="$stage/betelgeuse-device"
mkdir -p "$root/bin/tests/device" "$root/bin/bench" "$root/lib/fallback" "$root/tests/device" "$root/examples/scenes"

# The programs, without debug info unless PACK_DEBUG=1.
put() { # source, destination
	if [ "${PACK_DEBUG:-0}" = 1 ]; then cp "$1" "$2"; else strip --strip-debug -o "$2" "$1"; fi || exit 1
}
for t in "$build"/tests/test_*; do
	case $t in *.d) continue ;; esac
	put "$t" "$root/bin/tests/$(basename "$t")"
done
put "$build/tests/probe_headless" "$root/bin/tests/probe_headless"
put "$build/tests/device/crash_suite" "$root/bin/tests/device/crash_suite"
put "$build/tests/device/device_info" "$root/bin/tests/device/device_info"
put "$build/bench/bench_frame_cost" "$root/bin/bench/bench_frame_cost"
put "$build/bench/bench_paper" "$root/bin/bench/bench_paper"
put "$build/bench/bench_distribution" "$root/bin/bench/bench_distribution"
put "$build/betelgeuse" "$root/bin/betelgeuse"

# Their libraries: everything ldd resolves but the C library's own files (the machine's must be
# used: they go with its loader) and the toolchain's runtime (lib/fallback).
find "$root/bin" -type f -exec ldd {} + 2>/dev/null | awk '$2 == "=>" && $3 ~ /^\// { print $1, $3 }' | sort -u |
	while read -r soname path; do
		case $soname in
		linux-vdso* | ld-linux* | libc.so.* | libm.so.* | libdl.so.* | libpthread.so.* | librt.so.* | \
			libresolv.so.* | libutil.so.* | libanl.so.* | libmvec.so.*) ;;
		libstdc++.so.* | libgcc_s.so.*) cp -L "$path" "$root/lib/fallback/$soname" ;;
		*) cp -L "$path" "$root/lib/$soname" ;;
		esac
	done
missing=$(find "$root/bin" -type f -exec ldd {} + 2>/dev/null | grep 'not found' | sort -u)
[ -n "$missing" ] && { echo "device-pack: libraries not found here:"; echo "$missing"; exit 1; }

cp tests/run_suites.sh "$root/tests/"
cp tests/device/check_runner.sh "$root/tests/device/"
cp -R tests/data "$root/tests/"
cp -R examples/scenes/json "$root/examples/scenes/"
[ -f build/suite-times ] && cp build/suite-times "$root/suite-times"

# What the machine must offer: the newest C library symbol version any packed file needs.
glibc_needed() {
	find "$@" -type f -exec objdump -T {} + 2>/dev/null | awk '/\*UND\*/ && match($0, /GLIBC_[0-9.]+/) {
		print substr($0, RSTART + 6, RLENGTH - 6) }' | sort -t. -k1,1n -k2,2n -k3,3n | tail -n1
}
{
	echo "commit: $(git rev-parse --short HEAD 2>/dev/null)$(git diff --quiet HEAD 2>/dev/null || echo ' (with changes not committed)')"
	echo "packed: $(date -u '+%Y-%m-%d %H:%M UTC') on $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME"), glibc $(getconf GNU_LIBC_VERSION | cut -d' ' -f2)"
	echo "needs: glibc $(glibc_needed "$root/bin" "$root/lib" -path "$root/lib/fallback" -prune -o) or later;" \
		"with lib/fallback: glibc $(glibc_needed "$root/lib/fallback")"
	echo "debug info: $([ "${PACK_DEBUG:-0}" = 1 ] && echo kept || echo stripped, symbols kept)"
} >"$root/manifest.txt"

echo "device-pack: compressing $(du -sh "$root" | cut -f1) (xz)"
rm -f "$dest/payload.tar.xz"
tar cf - -C "$stage" betelgeuse-device | xz -6 -T2 >"$dest/payload.tar.xz" || exit 1
cp tests/device/run.sh "$dest/run.sh"

# glvnd's EGL and GL dispatch libraries, which a bare CUDA image lacks (the device tool's README):
# fetched once with apt-get download, kept between packs.
mkdir -p "$dest/debs"
if ! ls "$dest"/debs/*.deb >/dev/null 2>&1; then
	if command -v apt-get >/dev/null 2>&1 && [ "$(dpkg --print-architecture 2>/dev/null)" = amd64 ]; then
		(cd "$dest/debs" && apt-get download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null 2>&1) ||
			echo "device-pack: apt-get download of glvnd's packages failed: put libegl1, libglvnd0, libopengl0, libgl1," \
				"libglx0 and libgles2 (amd64 .deb files) into $dest/debs"
	else
		echo "device-pack: no apt-get here: put glvnd's amd64 .deb files into $dest/debs"
	fi
fi

cat "$root/manifest.txt"
echo "device-pack: $dest: payload $(du -sh "$dest/payload.tar.xz" | cut -f1), debs $(du -sh "$dest/debs" | cut -f1)," \
	"$(du -sh "$dest" | cut -f1) in all ($(du -sk "$dest" | cut -f1) KiB of the 65536 KiB a GPU machine is sent," \
	"with the working tree: $(git ls-files -z 2>/dev/null | xargs -0 cat 2>/dev/null | wc -c | awk '{ printf "%d", $1 / 1024 }') KiB more)"
