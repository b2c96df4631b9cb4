#!/bin/sh
# `make install` into a scratch DESTDIR, then a tiny program (tests/install_example.c)
# compiled and linked against the installed bitrain.pc, and run.  Ends with
# "N passed, N failed" like the test programs.  Usage: mk/check-install.sh [make]
MAKE=${1:-make}
tmp=${TMPDIR:-/tmp}/bitrain-install.$$
trap 'rm -rf "$tmp"' EXIT INT TERM
mkdir -p "$tmp"
fail() { echo "check-install: $*"; echo "0 passed, 1 failed"; exit 1; }
$MAKE --no-print-directory -s install DESTDIR="$tmp/root" PREFIX=/usr >"$tmp/log" 2>&1 || { cat "$tmp/log"; fail "make install failed"; }
for f in usr/bin/bitrain usr/lib/libbitrain.a usr/lib/pkgconfig/bitrain.pc usr/include/bitrain/raster/raster.h; do
  [ -f "$tmp/root/$f" ] || fail "make install did not install /$f"
done
PKG_CONFIG_PATH="$tmp/root/usr/lib/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$tmp/root"
export PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR
flags=$(pkg-config --cflags --static --libs bitrain) || fail "pkg-config does not read the installed bitrain.pc"
${CC:-cc} -std=c99 -o "$tmp/example" tests/install_example.c $flags || fail "tests/install_example.c does not build against the installed bitrain ($flags)"
"$tmp/example" || fail "tests/install_example.c built against the installed bitrain failed"
echo "1 passed, 0 failed"
