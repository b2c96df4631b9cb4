#!/bin/sh
# `make install` into a scratch DESTDIR, then a tiny program (tests/install_example.c)
# compiled and linked against the installed bitrain.pc, and run; then the installed
# program run on its bundled terrain from another directory; then an install with no
# DESTDIR and another BINDIR, whose program and library find the terrain in DATADIR.  Ends with
# "N passed, N failed" like the test programs.  Usage: mk/check-install.sh [make]
MAKE=${1:-make}
tmp=${TMPDIR:-/tmp}/bitrain-install.$$
trap 'rm -rf "$tmp"' EXIT INT TERM
mkdir -p "$tmp"
fail() { echo "check-install: $*"; echo "0 passed, 1 failed"; exit 1; }
$MAKE --no-print-directory -s install DESTDIR="$tmp/root" PREFIX=/usr >"$tmp/log" 2>&1 || { cat "$tmp/log"; fail "make install failed"; }
for f in usr/bin/bitrain usr/lib/libbitrain.a usr/lib/pkgconfig/bitrain.pc usr/include/bitrain/raster/raster.h \
         usr/share/bitrain/N47E009.hgt.gz usr/share/bitrain/default-path.cam; do
  [ -f "$tmp/root/$f" ] || fail "make install did not install /$f"
done
PKG_CONFIG_PATH="$tmp/root/usr/lib/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$tmp/root"
export PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR
flags=$(pkg-config --cflags --static --libs bitrain) || fail "pkg-config does not read the installed bitrain.pc"
${CC:-cc} -std=c99 -o "$tmp/example" tests/install_example.c $flags || fail "tests/install_example.c does not build against the installed bitrain ($flags)"
"$tmp/example" || fail "tests/install_example.c built against the installed bitrain failed"
# The installed program finds the bundled terrain and camera paths in share/bitrain from
# any directory (platform/assets.h): `bitrain run` without a display, a default-scene
# benchmark along a named path; without them it says where it looked.
bin="$tmp/root/usr/bin/bitrain"
mkdir -p "$tmp/elsewhere"
(cd "$tmp/elsewhere" && env -u DISPLAY -u WAYLAND_DISPLAY "$bin" run >"$tmp/run.log" 2>&1) \
  || { cat "$tmp/run.log"; fail "the installed bitrain run failed outside the source tree"; }
[ -s "$tmp/elsewhere/out/terrain.png" ] || fail "the installed bitrain run wrote no out/terrain.png"
(cd "$tmp/elsewhere" && "$bin" bench --scene default --path assets/lake-path.cam --frames 1 --size 64x48 >"$tmp/bench.log" 2>&1) \
  || { cat "$tmp/bench.log"; fail "the installed bitrain bench --scene default failed outside the source tree"; }
mv "$tmp/root/usr/share/bitrain" "$tmp/moved"
(cd "$tmp/elsewhere" && BITRAIN_ASSETS="$tmp/moved" "$bin" bench --scene default --frames 1 --size 64x48 >"$tmp/bench.log" 2>&1) \
  || { cat "$tmp/bench.log"; fail "BITRAIN_ASSETS does not point the installed bitrain at its assets"; }
(cd "$tmp/elsewhere" && "$bin" bench --scene default --frames 1 --size 64x48 >"$tmp/bench.log" 2>&1) \
  && fail "the installed bitrain ran without its assets"
grep -q "assets/N47E009.hgt.gz: cannot open (looked in ./assets, .*/usr/bin/assets, .*/usr/share/bitrain and /usr/share/bitrain)" "$tmp/bench.log" \
  || { cat "$tmp/bench.log"; fail "without its assets the installed bitrain does not say where it looked"; }
# Installed for real (no DESTDIR) with the program in another BINDIR: the program and a
# program linked against the installed library find the data in the DATADIR they were
# built for (ASSET_DATADIR), from any directory, with no BITRAIN_ASSETS.
unset PKG_CONFIG_SYSROOT_DIR
$MAKE --no-print-directory -s install PREFIX="$tmp/p" BINDIR="$tmp/bin2" >"$tmp/log" 2>&1 || { cat "$tmp/log"; fail "make install PREFIX=$tmp/p failed"; }
(cd "$tmp/elsewhere" && env -u BITRAIN_ASSETS "$tmp/bin2/bitrain" bench --scene default --frames 1 --size 64x48 >"$tmp/bench.log" 2>&1) \
  || { cat "$tmp/bench.log"; fail "bitrain installed in another BINDIR does not find its DATADIR"; }
PKG_CONFIG_PATH="$tmp/p/lib/pkgconfig"
flags=$(pkg-config --cflags --static --libs bitrain) || fail "pkg-config does not read $tmp/p's bitrain.pc"
${CC:-cc} -std=c99 -o "$tmp/example2" tests/install_example.c $flags || fail "tests/install_example.c does not build against $tmp/p"
(cd "$tmp/elsewhere" && env -u BITRAIN_ASSETS "$tmp/example2" >"$tmp/example.log" 2>&1) \
  || { cat "$tmp/example.log"; fail "a program linked against the installed library does not find the bundled terrain"; }
echo "3 passed, 0 failed"
