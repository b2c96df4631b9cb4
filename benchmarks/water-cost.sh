#!/bin/sh
# benchmarks/water-cost.sh — what water, sky and fog add to the frame users see (issue 18):
# callgrind instructions a frame of `bitrain bench --scene default` along the whole of
# assets/default-path.cam and assets/lake-path.cam, at 320x240 and 640x480, with water
# and fog off (the benchmark of record) and with the default water (half-resolution
# reflection + fog), and their ratio (the goal: at most 1.4x).  The whole path, not its
# first frames: the lake path's second half flies low over open water, where the water's
# pixels are most of the screen.  WATER_FRAMES=N measures the first N frames instead.
# Needs valgrind (skipped without it).  Run from make bench (./bitrain built).
cd "$(dirname "$0")/.." || exit 1
[ -x ./bitrain ] || { echo "skipped: ./bitrain not built"; exit 0; }
command -v valgrind >/dev/null 2>&1 || { echo "skipped: no valgrind"; exit 0; }
mkdir -p benchmarks/out
ir() {  # ir OUT args...: instructions in bench_default_frame
  out=benchmarks/out/callgrind.water.$1; shift
  valgrind --tool=callgrind --toggle-collect=bench_default_frame --callgrind-out-file="$out" \
    ./bitrain bench --scene default "$@" >/dev/null 2>&1 || return 1
  callgrind_annotate "$out" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }'
}
for size in 320x240 640x480; do
  for p in default lake; do
    path=assets/$p-path.cam
    n=${WATER_FRAMES:-$(grep -cv '^[[:space:]]*\(#\|$\)' "$path")}
    off=$(ir "$p.$size.off" --path "$path" --size "$size" --frames "$n") || { echo "$p $size: bench failed"; exit 1; }
    on=$(ir "$p.$size.on" --path "$path" --size "$size" --frames "$n" --with-water) || { echo "$p $size: bench failed"; exit 1; }
    awk -v off="$off" -v on="$on" -v n="$n" -v p="$p" -v s="$size" 'BEGIN {
      r = on / off
      printf "  %s path %s, %d frames: water off %.2f M, half-res reflection + fog %.2f M a frame: %.3fx (goal 1.4x: %s)\n",
             p, s, n, off / n / 1e6, on / n / 1e6, r, r <= 1.4 ? "met" : "not met" }'
  done
done
