#!/bin/sh
# benchmarks/arm-count.sh — instructions per frame of the peer scene (../shared/bench/PEERS.md,
# the frames of `bitrain bench --scene peer`) on ARM, counted under qemu-user by the TCG
# plugin benchmarks/qemu_insn.c, next to x86-64 (valgrind callgrind) from the SAME harness:
#   benchmarks/arm/peer_dump  (native, libpng) writes the scene + cameras as a raw file and
#                             renders the reference frame the way bitrain bench does;
#   benchmarks/arm/peer_run   (core/ + raster/ only, static for ARM) reads it and renders
#                             N frames (XRGB8888, 32-bit depth, culling off, one band).
# Instructions per frame = (count(11 frames) - count(1 frame)) / 10: loading, set-up and the
# checksum cancel.  Every run's last-frame checksum must equal the native reference
# (cross-architecture identity); a difference is reported as a FAILURE (exit 1).
# Columns: x86-64 (cc -O2, callgrind), aarch64 (-O2), armhf (-O2, Debian default armv7-a
# Thumb-2, no hardware divide), armhf-a7 (-O2 -mcpu=cortex-a7: hardware 32-bit divide).
# qemu runs a Raspberry-Pi-class CPU model (aarch64: -cpu cortex-a72, armhf: -cpu cortex-a7) so
# static glibc's ifuncs pick what such a board picks (qemu's default "max" CPU gives SVE memcpy).  A missing compiler/qemu/valgrind gives "-" in its column;
# with no qemu or no cross compiler at all it prints "skipped: ..." and exits 0.
# Then the same for the configuration of a board without a framebuffer (RGB565, 16-bit depth,
# 16-row bands with the chunk table; checksums against the native run of the same harness).
# Then the per-function top list of one configuration (per frame, from the per-TB counts and
# nm; static functions inlined into others count as their caller), with the libgcc helpers.
#
# Usage: sh benchmarks/arm-count.sh        (from anywhere)
#   SIZES="640x480 320x240"  CAMS="A B"    the configurations
#   BOARD_SIZE=320x240                     size of the board configuration (RGB565, 16-bit
#                                          depth, 16-row bands): its own table
#   TOP="armhf A 640x480"                  target, camera, size of the per-function list
#   NTOP=15                                length of that list
#   OUT=benchmarks/out/arm-count           build and output directory (raw counts stay there)
#   DEM=../shared/data/dem/png/fuji.png    the peer scene's height map
set -u
cd "$(dirname "$0")/.." || exit 1
SIZES=${SIZES:-640x480 320x240}
BOARD_SIZE=${BOARD_SIZE:-320x240}
CAMS=${CAMS:-A B}
TOP=${TOP:-armhf A 640x480}
NTOP=${NTOP:-15}
OUT=${OUT:-benchmarks/out/arm-count}
DEM=${DEM:-../shared/data/dem/png/fuji.png}
CC=${CC:-cc}
WARN="-Wall -Wextra -Wshadow -Wundef -Wwrite-strings -Wdouble-promotion -Wmissing-prototypes -Wstrict-prototypes -Wconversion -Wno-sign-conversion"
RSRC="$(ls core/*.c raster/*.c)"
# name  compiler  qemu  [-cpu model]  flags...
TARGETS="aarch64:aarch64-linux-gnu-gcc:qemu-aarch64:cortex-a72:-O2
armhf:arm-linux-gnueabihf-gcc:qemu-arm:cortex-a7:-O2
armhf-a7:arm-linux-gnueabihf-gcc:qemu-arm:cortex-a7:-O2 -mcpu=cortex-a7"

have() { command -v "$1" >/dev/null 2>&1; }
if ! have qemu-aarch64 && ! have qemu-arm; then echo "skipped: no qemu-aarch64 or qemu-arm"; exit 0; fi
if ! have aarch64-linux-gnu-gcc && ! have arm-linux-gnueabihf-gcc; then echo "skipped: no ARM cross compiler"; exit 0; fi
if [ ! -f "$DEM" ]; then echo "skipped: $DEM not found (set DEM=)"; exit 0; fi
if ! pkg-config --exists libpng 2>/dev/null; then echo "skipped: libpng (pkg-config) not found for peer_dump"; exit 0; fi
mkdir -p "$OUT" || exit 1

# ---- builds ----
$CC -std=c99 -O2 $WARN -shared -fPIC -fvisibility=hidden -o "$OUT/qemu_insn.so" benchmarks/qemu_insn.c \
  || { echo "arm-count: cannot build the qemu plugin"; exit 1; }
$CC -std=c99 -O2 $WARN -I. $(pkg-config --cflags libpng) -o "$OUT/peer_dump" benchmarks/arm/peer_dump.c \
  benchmarks/peer_scene.c platform/png_io.c platform/err.c $RSRC $(pkg-config --libs libpng zlib) -lm \
  || { echo "arm-count: cannot build peer_dump"; exit 1; }
$CC -std=c99 -O2 $WARN -I. -o "$OUT/peer_run-x86-64" benchmarks/arm/peer_run.c $RSRC \
  || { echo "arm-count: cannot build the native peer_run"; exit 1; }
"$OUT/peer_dump" "$DEM" "$OUT/scene.bin" || { echo "arm-count: peer_dump failed"; exit 1; }
cols="x86-64"
have valgrind || echo "note: valgrind not found, no x86-64 column"
echo "$TARGETS" | while IFS=: read -r name cc q cpu flags; do
  rm -f "$OUT/peer_run-$name"
  if ! have "$cc" || ! have "$q"; then echo "note: $name skipped ($cc or $q not installed)"; continue; fi
  # shellcheck disable=SC2086
  "$cc" -std=c99 $flags -static $WARN -I. -o "$OUT/peer_run-$name" benchmarks/arm/peer_run.c $RSRC \
    || { echo "note: $name: build failed"; rm -f "$OUT/peer_run-$name"; continue; }
  "${cc%gcc}nm" -n --defined-only "$OUT/peer_run-$name" > "$OUT/nm-$name" 2>/dev/null || nm -n "$OUT/peer_run-$name" > "$OUT/nm-$name"
  if ! $q ${cpu:+-cpu $cpu} -plugin "$OUT/qemu_insn.so,out=$OUT/probe.txt" "$OUT/peer_run-$name" >/dev/null 2>&1 \
     || ! [ -s "$OUT/probe.txt" ]; then
    :  # usage error exit (2) is expected; only the counts file matters
  fi
  if ! grep -q '^total ' "$OUT/probe.txt" 2>/dev/null; then
    echo "note: $name skipped ($q cannot load the plugin)"; rm -f "$OUT/peer_run-$name"
  fi
  rm -f "$OUT/probe.txt"
done

# ---- runs ----
fail=0
count_qemu() { # name q cpu cam size frames [board] -> prints total, leaves $OUT/tb-...
  f="$OUT/tb-$1-$4-$5-$6${7:+-$7}.txt"
  $2 ${3:+-cpu $3} -plugin "$OUT/qemu_insn.so,out=$f" "$OUT/peer_run-$1" "$OUT/scene.bin" "$4" "$5" "$6" ${7:-} \
    > "$OUT/run-$1-$4-$5-$6${7:+-$7}.txt" || return 1
  sed -n 's/^total //p' "$f"
}
count_cg() { # cam size frames [board]
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$OUT/peer_run-x86-64" "$OUT/scene.bin" "$1" "$2" "$3" ${4:-} \
    2> "$OUT/cg-$1-$2-$3${4:+-$4}.err" > "$OUT/run-x86-64-$1-$2-$3${4:+-$4}.txt" || return 1
  sed -n 's/.*Collected : *//p' "$OUT/cg-$1-$2-$3${4:+-$4}.err" | tr -d ','
}
# one table row: cam size ref line-so-far bad-so-far [board]; counts per target (x86-64 by
# callgrind when valgrind is there), every run's checksum against ref; sets fail on a mismatch
row() {
  cam=$1; size=$2; ref=$3; line=$4; bad=$5; mode=${6:-}; sfx=${mode:+-$mode}
  if have valgrind; then
    c1=$(count_cg "$cam" "$size" 1 $mode); c11=$(count_cg "$cam" "$size" 11 $mode)
    if [ -n "$c1" ] && [ -n "$c11" ]; then
      line="$line $(echo "$c1 $c11" | awk '{ printf "%12.3f", ($2 - $1) / 10 / 1e6 }')"
      grep -q "checksum=$ref " "$OUT/run-x86-64-$cam-$size-11$sfx.txt" || bad="$bad x86-64(cg)"
    else line="$line $(printf '%12s' failed)"; fi
  else line="$line $(printf '%12s' -)"; fi
  for t in aarch64 armhf armhf-a7; do
    spec=$(echo "$TARGETS" | grep "^$t:")
    q=$(echo "$spec" | cut -d: -f3); cpu=$(echo "$spec" | cut -d: -f4)
    if [ ! -x "$OUT/peer_run-$t" ]; then line="$line $(printf '%12s' -)"; continue; fi
    c1=$(count_qemu "$t" "$q" "$cpu" "$cam" "$size" 1 $mode); c11=$(count_qemu "$t" "$q" "$cpu" "$cam" "$size" 11 $mode)
    if [ -n "$c1" ] && [ -n "$c11" ]; then
      line="$line $(echo "$c1 $c11" | awk '{ printf "%12.3f", ($2 - $1) / 10 / 1e6 }')"
    else line="$line $(printf '%12s' failed)"; bad="$bad $t(run)"; continue; fi
    for n in 1 11; do grep -q "checksum=$ref " "$OUT/run-$t-$cam-$size-$n$sfx.txt" || bad="$bad $t"; done
  done
  if [ -z "$bad" ]; then echo "$line   $ref all equal"
  else echo "$line   $ref MISMATCH:$bad"; fail=1; fi
}
printf '%-14s %12s %12s %12s %12s   %s\n' "M insn/frame" "x86-64" "aarch64" "armhf" "armhf-a7" "checksum (last frame)"
for size in $SIZES; do
  for cam in $CAMS; do
    ref=$("$OUT/peer_dump" "$DEM" "$OUT/scene-check.bin" "$cam" "$size" | sed 's/.*checksum=\([0-9a-f]*\).*/\1/')
    line=$(printf '%-14s' "$cam $size")
    "$OUT/peer_run-x86-64" "$OUT/scene.bin" "$cam" "$size" 2 > "$OUT/run-native-$cam-$size.txt"
    bad=""
    grep -q "checksum=$ref " "$OUT/run-native-$cam-$size.txt" || bad=" x86-64"
    row "$cam" "$size" "$ref" "$line" "$bad"
  done
done
rm -f "$OUT/scene-check.bin"

# ---- the configuration of a board without a framebuffer ----
# RGB565, 16-bit depth, 16-row bands into one band buffer, chunk table (peer_run ... board);
# every target's checksum over the bands must equal the native one.
echo
echo "board configuration (RGB565, 16-bit depth, bands of 16 rows with the chunk table), $BOARD_SIZE:"
printf '%-14s %12s %12s %12s %12s   %s\n' "M insn/frame" "x86-64" "aarch64" "armhf" "armhf-a7" "checksum (bands)"
for cam in $CAMS; do
  size=$BOARD_SIZE
  "$OUT/peer_run-x86-64" "$OUT/scene.bin" "$cam" "$size" 2 board > "$OUT/run-native-$cam-$size-board.txt"
  ref=$(sed 's/.*checksum=\([0-9a-f]*\).*/\1/' "$OUT/run-native-$cam-$size-board.txt")
  row "$cam" "$size" "$ref" "$(printf '%-14s' "$cam $size")" "" board
done
if [ $fail != 0 ]; then
  echo "FAILURE: a target's frame differs from the native reference (cross-architecture identity broken);"
  echo "         the runs' outputs are in $OUT/run-*.txt"
fi

# ---- per-function list ----
set -- $TOP
t=$1; cam=$2; size=$3
if [ -f "$OUT/tb-$t-$cam-$size-1.txt" ] && [ -f "$OUT/tb-$t-$cam-$size-11.txt" ]; then
  echo
  echo "$t camera $cam $size: top $NTOP functions, M instructions per frame (calls per frame: entries of the"
  echo "function's first block; static functions inlined into a caller count as the caller)"
  awk -v ntop="$NTOP" '
    function hex(s,  i, v) { v = 0; s = tolower(s)
      for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
      return v }
    function find(a,  lo, hi, mid) { if (ns == 0 || a < sa[1]) return 0; lo = 1; hi = ns
      while (lo < hi) { mid = int((lo + hi + 1) / 2); if (sa[mid] <= a) lo = mid; else hi = mid - 1 }
      return lo }
    FILENAME == ARGV[1] { if (NF >= 3 && $2 ~ /^[tTwW]$/) { a = hex($1); a -= a % 2; sa[++ns] = a; sn[ns] = $3 }; next }
    FNR == 1 { run++; if (run == 1) t1 = $2; else t11 = $2; next }
    { a = hex($1); k = find(a); name = k ? sn[k] : "?"; c = $2 * $3; s = (run == 1) ? -1 : 1
      d[name] += s * c; if (k && sa[k] == a) calls[name] += s * $3 }
    END {
      tot = (t11 - t1) / 10
      for (n in d) if (d[n] > 0) printf "%.1f %s %.1f\n", d[n] / 10, n, calls[n] / 10
      printf "TOTAL %.1f\n", tot > "/dev/stderr"
    }' "$OUT/nm-$t" "$OUT/tb-$t-$cam-$size-1.txt" "$OUT/tb-$t-$cam-$size-11.txt" 2> "$OUT/top-total.txt" \
    | sort -k1,1nr > "$OUT/top-$t-$cam-$size.txt"
  tot=$(sed -n 's/^TOTAL //p' "$OUT/top-total.txt")
  head -n "$NTOP" "$OUT/top-$t-$cam-$size.txt" | awk -v tot="$tot" '
    { printf "  %-28s %9.3f M  %5.1f%%  %10.0f calls\n", $2, $1 / 1e6, 100 * $1 / tot, $3 }'
  awk -v tot="$tot" '$2 ~ /^__(aeabi_|gnu_|u?divmoddi4|u?divdi3|u?moddi3|u?divsi3|[cf]tz|clz|muldi3|ashldi3|ashrdi3|lshrdi3|divmodsi4)/ {
      s += $1; l = l " " $2 }
    END { printf "  libgcc arithmetic helpers:   %9.3f M  %5.1f%% of %.3f M  (%s )\n", s / 1e6, tot ? 100 * s / tot : 0, tot / 1e6, l }' \
    "$OUT/top-$t-$cam-$size.txt"
  rm -f "$OUT/top-total.txt"
fi
exit $fail
