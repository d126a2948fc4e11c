#!/bin/sh
# make check-no-osmesa: the project on a machine without OSMesa (Mesa 25.1 and later ship none),
# made here by hiding every libOSMesa file of this one: inside a private mount namespace (unshare -m,
# as root) /dev/null is mounted over each, so that loading one fails as it would where the file is
# missing, for this process and its children only.
#
# Then the backend probe must say OSMesa cannot be loaded (else nothing was hidden and the check
# proves nothing), the smoke suites and a GPU scene suite run on EGL surfaceless through the suite
# runner, with their OSMesa runs counted as skipped, and the command renders a shipped scene with
# its default backend order. A program that links libOSMesa fails to start here, and one that needs
# it at run time fails its suite: either fails this check.
# Usage: check_no_osmesa.sh BUILD_DIR "suite binaries" "smoke suite binaries"
set -eu
build=$1
suites=$2
smoke=$3

if [ "${BG_OSMESA_HIDDEN:-}" != yes ]; then
	if [ "$(id -u)" != 0 ] || ! command -v unshare >/dev/null; then
		echo "check-no-osmesa: needs root and unshare (util-linux) to hide OSMesa in a mount namespace" >&2
		exit 1
	fi
	exec unshare -m env BG_OSMESA_HIDDEN=yes sh "$0" "$@"
fi

# Every libOSMesa the loader knows of, and any file by that name in the usual folders (a link
# resolves to its target, which is then hidden).
libs=$({ ldconfig -p | sed -n 's/.*libOSMesa\.so[^ ]* .*=> \(.*\)$/\1/p'
	ls /lib/*/libOSMesa.so* /usr/lib/*/libOSMesa.so* /usr/lib/libOSMesa.so* /usr/local/lib/libOSMesa.so* 2>/dev/null
} | sort -u)
for f in $libs; do
	[ -e "$f" ] && mount --bind /dev/null "$f"
done
echo "== check-no-osmesa: hidden $(echo $libs | wc -w) libOSMesa files: $(echo $libs)"

if why=$("$build/tests/probe_headless" osmesa); then
	echo "FAIL check-no-osmesa: OSMesa still gives a context, nothing was hidden"
	exit 1
fi
echo "the probe: $why"

TEST_ENV="$TEST_ENV" PROBE="$build/tests/probe_headless" sh tests/run_suites.sh "$suites" "$smoke"

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# shellcheck disable=SC2086 # TEST_ENV is a list of NAME=value words
env $TEST_ENV "$build/betelgeuse" render examples/scenes/json/paper_earth_shadow.json --size 160x120 \
	-o "$out/earth.png" --quiet
[ -s "$out/earth.png" ] || { echo "FAIL check-no-osmesa: the command wrote no image"; exit 1; }
echo "check-no-osmesa: the command rendered $(wc -c <"$out/earth.png") bytes of PNG without OSMesa"
