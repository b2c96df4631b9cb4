#!/bin/sh
# Make sure the system packages bitrain builds with are present.
# On Debian/Ubuntu, missing ones are installed with apt-get (through sudo when
# not root) and we say so; elsewhere we stop and print what to install.
# Usage: mk/deps.sh [--optional] [extra-debian-package...]
#   --optional: the extra packages only widen what the tests cover (cross
#   compilers, qemu); when they cannot be installed we say so and go on.
set -u
optional=0
if [ "${1:-}" = "--optional" ]; then optional=1; shift; fi
need=""
have_pc() { pkg-config --exists "$1" 2>/dev/null; }
command -v cc >/dev/null 2>&1 || need="$need gcc"
command -v make >/dev/null 2>&1 || need="$need make"
command -v pkg-config >/dev/null 2>&1 || need="$need pkg-config"
have_pc libpng || need="$need libpng-dev"
have_pc zlib || need="$need zlib1g-dev"
have_pc sdl2 || need="$need libsdl2-dev"
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need="$need $p"
done
[ -z "$need" ] && exit 0
if command -v apt-get >/dev/null 2>&1 && command -v dpkg-query >/dev/null 2>&1; then
  sudo=""
  if [ "$(id -u)" != 0 ]; then
    if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
      echo "bitrain: missing packages:$need; run as root: apt-get install -y$need" >&2; exit $((1 - optional))
    fi
  fi
  echo "bitrain: installing missing system packages:$need (apt-get)"
  if ! $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q $need >/tmp/bitrain-apt.log 2>&1; then
    echo "bitrain: apt-get install failed; refreshing the package lists (apt-get update) and trying again"
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q >>/tmp/bitrain-apt.log 2>&1
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q $need >>/tmp/bitrain-apt.log 2>&1 || {
      echo "bitrain: apt-get install$need failed; see /tmp/bitrain-apt.log" >&2; exit $((1 - optional)); }
  fi
  echo "bitrain: installed$need"
  exit 0
fi
echo "bitrain: this is not a Debian-like system; please install the equivalents of:$need" >&2
echo "  (a C99 compiler, make, pkg-config, and the development files of libpng, zlib and SDL2)" >&2
exit $((1 - optional))
