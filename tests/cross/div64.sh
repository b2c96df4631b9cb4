#!/bin/sh
# No 64-bit division in a frame on 32-bit ARM (issue 20): the frames built for armhf
# (Debian's default armv7-a Thumb-2: no divide instruction, so a 64-bit `/` or `%` is a
# call of libgcc's __aeabi_ldivmod / __aeabi_uldivmod, which call __udivmoddi4) and run
# under qemu-arm with the instruction-count plugin (benchmarks/qemu_insn.c: executions
# per translation block).  A call enters a helper at its first instruction, so the
# executions of the blocks that start there count its calls.  Each run is made twice,
# with fewer and with FRAMES more frames; the difference is what those frames called,
# and it must be 0 for every helper.  The set-up's own calls (nonzero) show the count
# works.
#  1. tests/cross/frame_div.c: the default scene's terrain frame from core/ and raster/
#     alone (board configuration, SIZE), 0 frames against FRAMES.
#  2. The product's own frame with water, fog and sky, as `bitrain render` and `view`
#     draw the default scene: `bitrain bench --scene default --with-water` from the
#     whole library built for armhf without a display (mk/cross.mk, with the zlib and
#     libpng of mk/cross-libs.sh; tests/cross/bench_main.c), WARM frames against
#     WARM + FRAMES (the first frames size the band memory), in the board's layout
#     (RGB565, 16-bit depth, 16-row bands) and the viewer's (XRGB8888, 32-bit depth,
#     64-row bands); beside it the same frames without water, for the instructions a
#     frame.  Skipped (and counted so) when the target's zlib or libpng cannot be built.
# Prints the calls and instructions per frame; ends with "N passed, N failed" (",
# N skipped" with the reason when the cross compiler, qemu-arm, plugin support or the
# DEM is missing).
#   PATHS="default lake" FRAMES=3 WARM=2 SIZE=320x240 OUT=tests/out/div64
set -u
cd "$(dirname "$0")/../.." || exit 1
PATHS=${PATHS:-default lake}
FRAMES=${FRAMES:-3}
WARM=${WARM:-2}
SIZE=${SIZE:-320x240}
OUT=${OUT:-tests/out/div64}
dem=${BITRAIN_DATA:-../shared/data/dem}/hgt/N47E009.hgt
HELPERS="__aeabi_ldivmod __aeabi_uldivmod __udivmoddi4 __divdi3 __udivdi3 __moddi3 __umoddi3 __divmoddi4"
skip() { echo "skip   div64: $1"; echo "0 passed, 0 failed, 1 skipped"; exit 0; }
have() { command -v "$1" >/dev/null 2>&1; }
have arm-linux-gnueabihf-gcc || skip "arm-linux-gnueabihf-gcc not installed (gcc-arm-linux-gnueabihf)"
have arm-linux-gnueabihf-nm || skip "arm-linux-gnueabihf-nm not installed (binutils-arm-linux-gnueabihf)"
have qemu-arm || skip "qemu-arm not installed (qemu-user)"
have "${CC:-cc}" || skip "no host compiler for the qemu plugin"
[ -f "$dem" ] || skip "$dem not found (BITRAIN_DATA)"
mkdir -p "$OUT" && rm -f "$OUT"/*.txt || exit 1
WARN="-Wall -Wextra -Wshadow -Wundef -Wwrite-strings -Wdouble-promotion -Wmissing-prototypes -Wstrict-prototypes -Wconversion -Wno-sign-conversion"
${CC:-cc} -std=c99 -O2 $WARN -shared -fPIC -fvisibility=hidden -o "$OUT/qemu_insn.so" benchmarks/qemu_insn.c \
  || { echo "div64: cannot build the qemu plugin"; echo "0 passed, 1 failed"; exit 1; }
arm-linux-gnueabihf-gcc -std=c99 -O2 $WARN -static -I. -o "$OUT/frame_div" tests/cross/frame_div.c core/*.c raster/*.c -lm \
  || { echo "div64: cannot build tests/cross/frame_div.c for armhf"; echo "0 passed, 1 failed"; exit 1; }
probe=$(qemu-arm -plugin "$OUT/qemu_insn.so,out=$OUT/probe.txt" "$OUT/frame_div" 2>&1 </dev/null)
[ -f "$OUT/probe.txt" ] || skip "this qemu-arm cannot load the TCG plugin: $probe"
# helper_addrs BINARY: $addrs, each helper linked into it as NAME:ADDRESS, the entry
# address as the plugin prints it (hex, no 0x, Thumb bit cleared)
helper_addrs() {
  arm-linux-gnueabihf-nm "$1" >"$OUT/nm.txt"
  addrs=""
  for h in $HELPERS; do
    a=$(awk -v n="$h" '$3 == n && ($2 == "T" || $2 == "t") { print $1; exit }' "$OUT/nm.txt")
    [ -n "$a" ] && addrs="$addrs $h:$(printf '%x' $((0x$a & ~1)))"
  done
}
helper_addrs "$OUT/frame_div"
[ -n "$addrs" ] || { echo "div64: no libgcc division helper in the armhf binary (nothing to count)"; echo "0 passed, 1 failed"; exit 1; }
calls() { # plugin output, address -> executions of the blocks that start there
  awk -v A="$2" '$1 == A { s += $3 } END { print s + 0 }' "$1"
}
run() { # path frames -> plugin output file; 1 on failure
  qemu-arm -cpu cortex-a7 -plugin "$OUT/qemu_insn.so,out=$OUT/$1-$2.txt" "$OUT/frame_div" "$dem" \
    "assets/$1-path.cam" "$2" "$SIZE" >"$OUT/$1-$2.log" 2>&1 || { cat "$OUT/$1-$2.log"; return 1; }
}
passed=0; failed=0; skipped=0
# check TAG FILE0 FILE1: every helper's calls in FILE1 beyond FILE0 (0 or a failure)
check() {
  bad=0; setup=0; line=""
  for ha in $addrs; do
    h=${ha%%:*}; a=${ha#*:}
    c0=$(calls "$2" "$a"); c1=$(calls "$3" "$a")
    setup=$((setup + c0))
    line="$line $h $(( (c1 - c0) / FRAMES ))/frame (set-up $c0);"
    [ "$c1" != "$c0" ] && bad=1
  done
  t0=$(awk '$1 == "total" { print $2 }' "$2"); t1=$(awk '$1 == "total" { print $2 }' "$3")
  echo "$1, $FRAMES frames:$line $(( (t1 - t0) / FRAMES )) instructions a frame"
  if [ "$setup" = 0 ]; then echo "FAIL $1: the set-up's calls were not seen either: the count does not work"; bad=1; fi
  if [ $bad = 0 ]; then passed=$((passed + 1)); else echo "FAIL $1: 64-bit division in a frame"; failed=$((failed + 1)); fi
}
for p in $PATHS; do
  if ! run "$p" 0 || ! run "$p" "$FRAMES"; then echo "FAIL $p path: frame_div did not run"; failed=$((failed + 1)); continue; fi
  check "$p path, terrain at $SIZE" "$OUT/$p-0.txt" "$OUT/$p-$FRAMES.txt"
done

# 2. the product's frame with water
xb=build/cross/armhf
if ! sh mk/cross-libs.sh arm-linux-gnueabihf arm-linux-gnueabihf-gcc "$xb/deps" >"$OUT/deps.log" 2>&1; then
  echo "skip   div64 water: no zlib/libpng for armhf (see $xb/deps.log)"; skipped=1
elif ! make --no-print-directory -f mk/cross.mk -j"${JOBS:-2}" XCC=arm-linux-gnueabihf-gcc XB="$xb" XDEPS="$xb/deps" \
       "$xb/libbitrain.a" >"$OUT/lib.log" 2>&1 \
     || ! arm-linux-gnueabihf-gcc -std=c99 -O2 $WARN -static -I. -o "$OUT/bench_main" tests/cross/bench_main.c \
       "$xb/libbitrain.a" -L"$xb/deps/lib" -lpng -lz -lm -lpthread >>"$OUT/lib.log" 2>&1; then
  echo "FAIL div64 water: cannot build tests/cross/bench_main.c for armhf"; tail -n 15 "$OUT/lib.log"; failed=$((failed + 1))
else
  helper_addrs "$OUT/bench_main"
  bench() { # tag frames args... -> $OUT/tag-frames.txt; 1 on failure
    t=$1; n=$2; shift 2
    qemu-arm -cpu cortex-a7 -plugin "$OUT/qemu_insn.so,out=$OUT/$t-$n.txt" "$OUT/bench_main" --scene default \
      --frames "$n" --size "$SIZE" "$@" >"$OUT/$t-$n.log" 2>&1 || { cat "$OUT/$t-$n.log"; return 1; }
  }
  for p in $PATHS; do
    for cfg in "board:--format rgb565 --depth 16 --bands 16 --with-water" "viewer:--with-water" "terrain:"; do
      name=${cfg%%:*}; args=${cfg#*:}; t="bench-$p-$name"
      case $name in
        board) what="water, RGB565, 16-bit depth, 16-row bands" ;;
        viewer) what="water, XRGB8888, 32-bit depth, 64-row bands" ;;
        *) what="no water, XRGB8888, 32-bit depth, 64-row bands" ;;
      esac
      if ! bench "$t" "$WARM" --path "assets/$p-path.cam" $args || ! bench "$t" $((WARM + FRAMES)) --path "assets/$p-path.cam" $args; then
        echo "FAIL $p path, bench ($what) did not run"; failed=$((failed + 1)); continue
      fi
      check "$p path, bench ($what) at $SIZE" "$OUT/$t-$WARM.txt" "$OUT/$t-$((WARM + FRAMES)).txt"
    done
  done
fi
if [ "$skipped" != 0 ]; then echo "$passed passed, $failed failed, $skipped skipped"; else echo "$passed passed, $failed failed"; fi
[ "$failed" = 0 ]
