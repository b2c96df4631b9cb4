#!/bin/sh
# zlib and libpng for a foreign target, built from Debian's source packages with the
# target's cross compiler into static libraries, so that the test programs can be
# linked statically and run under qemu-user without a target sysroot.
# Usage: mk/cross-libs.sh TRIPLET CC OUTDIR
#   OUTDIR/include (zlib.h, zconf.h, png.h, pngconf.h, pnglibconf.h) and
#   OUTDIR/lib (libz.a, libpng.a) on success; exit 1 with a message naming what
#   is missing otherwise.
# Why not the target's libpng-dev (Debian multiarch): it needs
# `dpkg --add-architecture` and an apt-get update for each architecture, its
# version must equal the host's libpng-dev exactly, and riscv64 has no packages in
# Debian 12.  The sources come once, through apt-get source with a private list of
# deb-src lines made from the system's own deb lines (nothing in /etc is changed),
# into build/cross/src.
set -u
triplet=$1; cc=$2; out=$3
src=${CROSS_SRC:-build/cross/src}
log=$out.log
mkdir -p "$src" "$(dirname "$out")"
[ -f "$out/lib/libpng.a" ] && [ -f "$out/lib/libz.a" ] && exit 0

fetch() { # the unpacked zlib and libpng1.6 trees under $src (z/, png/)
  [ -f "$src/z/zlib.h" ] && [ -f "$src/png/png.h" ] && return 0
  command -v apt-get >/dev/null 2>&1 || { echo "cross-libs: no apt-get to fetch the zlib and libpng sources" >&2; return 1; }
  a=$(cd "$src" && pwd)/apt
  mkdir -p "$a/parts" "$a/lists/partial" "$a/cache/archives/partial"
  # deb-src twins of the system's deb entries (one-line and deb822 formats)
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] && sed -n 's/^[[:space:]]*deb[[:space:]]/deb-src /p' "$f"
  done >"$a/parts/src.list"
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] && sed 's/^Types:.*/Types: deb-src/' "$f"
    echo
  done >"$a/parts/src.sources"
  o="-o Dir::Etc::SourceList=$a/parts/src.list -o Dir::Etc::SourceParts=$a/parts \
     -o Dir::State::Lists=$a/lists -o Dir::Cache=$a/cache -o APT::Sandbox::User=root -q"
  # shellcheck disable=SC2086
  # (a third-party entry without sources fails the update, not the source download)
  apt-get $o update >>"$log" 2>&1
  for p in zlib libpng1.6; do
    # the newest version first, then every other one the lists know (a mirror may
    # lag behind its security suite's index)
    # shellcheck disable=SC2086
    for v in "" $(apt-cache $o showsrc "$p" 2>/dev/null | sed -n 's/^Version: /=/p'); do
      # shellcheck disable=SC2086
      (cd "$src" && apt-get $o source --download-only "$p$v") >>"$log" 2>&1 && continue 2
      rm -f "$src/$p"_*
    done
    echo "cross-libs: apt-get source $p failed; see $log" >&2; return 1
  done
  unpack zlib z && unpack libpng1.6 png
}
unpack() { # package dir: dpkg-source applies Debian's patches; without it the upstream tarball
  rm -rf "${src:?}/$2"
  dsc=$(ls "$src/$1"_*.dsc 2>/dev/null | head -n 1)
  [ -n "$dsc" ] || { echo "cross-libs: no $1 source package in $src" >&2; return 1; }
  if command -v dpkg-source >/dev/null 2>&1; then
    (cd "$src" && dpkg-source -x "$(basename "$dsc")" "$2") >>"$log" 2>&1 && return 0
  fi
  orig=$(ls "$src/$1"_*.orig.tar.* | head -n 1)
  mkdir -p "$src/$2" && tar -xf "$orig" -C "$src/$2" --strip-components=1
}

fetch || exit 1
rm -rf "$out"; mkdir -p "$out/include" "$out/lib" "$out/obj/z" "$out/obj/png"
cp "$src/png/scripts/pnglibconf.h.prebuilt" "$out/include/pnglibconf.h"
cp "$src/z/zlib.h" "$src/z/zconf.h" "$src/png/png.h" "$src/png/pngconf.h" "$out/include/"
# libpng's SIMD filters off: plain C on every target (they only speed up decoding)
flags="-O2 -I$out/include -DPNG_ARM_NEON_OPT=0 -DPNG_INTEL_SSE_OPT=0 -DPNG_POWERPC_VSX_OPT=0 -DPNG_MIPS_MSA_OPT=0 -DPNG_LOONGARCH_LSX_OPT=0"
for f in adler32 compress crc32 deflate gzclose gzlib gzread gzwrite infback inffast inflate inftrees trees uncompr zutil; do
  "$cc" $flags -DHAVE_UNISTD_H -c -o "$out/obj/z/$f.o" "$src/z/$f.c" >>"$log" 2>&1 ||
    { echo "cross-libs: $triplet: compiling zlib $f.c failed; see $log" >&2; exit 1; }
done
for f in png pngerror pngget pngmem pngpread pngread pngrio pngrtran pngrutil pngset pngtrans pngwio pngwrite pngwtran pngwutil; do
  "$cc" $flags -c -o "$out/obj/png/$f.o" "$src/png/$f.c" >>"$log" 2>&1 ||
    { echo "cross-libs: $triplet: compiling libpng $f.c failed; see $log" >&2; exit 1; }
done
ar=$(dirname "$(command -v "$cc")")/$triplet-ar
[ -x "$ar" ] || ar=ar
"$ar" rcs "$out/lib/libz.a" "$out"/obj/z/*.o && "$ar" rcs "$out/lib/libpng.a" "$out"/obj/png/*.o
