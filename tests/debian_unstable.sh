#!/bin/sh
# Builds and tests the project on Debian unstable in a chroot, as root on any Debian host:
#   sh tests/debian_unstable.sh [ROOT] [REPO]   (defaults: /var/tmp/betelgeuse-sid, the current directory)
# Creates ROOT with mmdebstrap on the first run (the packages of .ci/run's install_packages less
# libosmesa6, which unstable no longer has since Mesa 25.1 dropped OSMesa, plus git), clones REPO's
# HEAD into ROOT/root/betelgeuse (again on every run), builds, and runs the README's test command.
# Environment: MIRROR (default http://deb.debian.org/debian), CHECK_JOBS (passed to make check).
set -eu
ROOT=${1:-/var/tmp/betelgeuse-sid}
REPO=$(cd "${2:-.}" && pwd)
MIRROR=${MIRROR:-http://deb.debian.org/debian}
PACKAGES=build-essential,pkg-config,libegl-dev,libegl-mesa0,libgl-dev,libgl1-mesa-dri,libpng-dev,\
libcmocka-dev,glslang-tools,valgrind,libcjson-dev,libassimp-dev,libturbojpeg0-dev,libstb-dev,\
slurm-wlm,munge,util-linux,libglfw3-dev,xvfb,xauth,xdotool,mesa-vulkan-drivers,git,ca-certificates

if [ ! -x "$ROOT/usr/bin/make" ]; then
	command -v mmdebstrap >/dev/null || apt-get install -y mmdebstrap
	# A mirror or snapshot older than its Release's Valid-Until (a week) is still wanted here.
	mmdebstrap --variant=apt --aptopt='Acquire::Check-Valid-Until "false"' \
		--include="$PACKAGES" sid "$ROOT" "$MIRROR"
fi

# What the suites need of a running system; unmounted however the script ends.
unmount() {
	for m in dev/shm dev/pts dev sys proc; do
		mountpoint -q "$ROOT/$m" && umount "$ROOT/$m"
	done
	return 0
}
trap unmount EXIT INT TERM
mount -t proc proc "$ROOT/proc"
mount -t sysfs sys "$ROOT/sys"
mount --bind /dev "$ROOT/dev"
mount --bind /dev/pts "$ROOT/dev/pts"
mount -t tmpfs shm "$ROOT/dev/shm"

rm -rf "$ROOT/root/betelgeuse"
git clone -q "$REPO" "$ROOT/root/betelgeuse"
git -C "$ROOT/root/betelgeuse" log -1 --format='commit %H'
chroot "$ROOT" dpkg-query -W -f='${Package} ${Version}\n' gcc libgl1-mesa-dri libegl-mesa0 \
	libcmocka-dev libassimp-dev libpng-dev libcjson-dev libstb-dev libturbojpeg0-dev
chroot "$ROOT" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root ${CHECK_JOBS:+CHECK_JOBS=$CHECK_JOBS} \
	bash -c 'cd /root/betelgeuse && time make -j2 all examples test-programs && time make check'
