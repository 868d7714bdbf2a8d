#!/bin/sh
# deps.sh — make sure the Debian packages pm builds and tests with are here.
# As root, installs what is missing; otherwise prints the apt-get line.
pkgs="build-essential pkg-config libopenexr-dev libopenmesh-dev libembree-dev libpng-dev libexpat1-dev zlib1g-dev libopenimageio-dev parallel"
# The tests also render the man pages (man-db, groff-base) and run programs
# on a pty (script, from bsdutils).
pkgs="$pkgs man-db groff-base bsdutils"
# Extras for one make target only: `deps.sh fuzz` (make fuzz: clang with
# libFuzzer and OpenMP), `deps.sh memcheck` (make memcheck: valgrind).
case "${1:-}" in
fuzz) pkgs="clang libclang-rt-14-dev libomp-dev" ;;
memcheck) pkgs="valgrind" ;;
# `deps.sh bench` (make bench, make bench-quick): plots and the kd-tree anchor.
bench) pkgs="gnuplot-nox libnanoflann-dev" ;;
# `deps.sh cluster` (make check-cluster): SLURM and its authentication daemon.
cluster) pkgs="slurm-wlm munge" ;;
# `deps.sh blender` (make check-blender): Blender, which runs the exporter.
blender) pkgs="blender" ;;
esac
missing=
for p in $pkgs; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' ||
		missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -eq 0 ]; then
	echo "deps: installing$missing"
	export DEBIAN_FRONTEND=noninteractive
	apt-get update -qq || exit 1
	apt-get install -y -qq --no-install-recommends $missing >/dev/null || exit 1
else
	echo "deps: missing packages; run as root:" >&2
	echo "  apt-get install$missing" >&2
	exit 1
fi
