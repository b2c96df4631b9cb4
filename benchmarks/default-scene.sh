#!/bin/sh
# benchmarks/default-scene.sh — the benchmark of record (issue 20): the terrain frame users
# see (bitrain bench --scene default: selection + strip + vertices + transform + raster in
# the viewer's 64-row bands, 1 px) on assets/N47E009.hgt.gz along the camera paths of
# assets/*.cam, at 320x240 and 640x480; instructions per frame by callgrind when valgrind
# is present (--toggle-collect=bench_default_frame), wall time and triangles per second
# (whole pipeline, and the rasteriser alone) and the share of the triangles that own a
# pixel (--visibility: docs/benchmarks.md) always.  Run from make bench (./bitrain built).
# FRAMES=N (default 30) frames per path.
cd "$(dirname "$0")/.." || exit 1
FRAMES=${FRAMES:-30}
[ -x ./bitrain ] || { echo "skipped: ./bitrain not built"; exit 0; }
mkdir -p benchmarks/out
for size in 320x240 640x480; do
  for p in default lake alps; do
    ./bitrain bench --scene default --path assets/$p-path.cam --size $size --frames "$FRAMES" || exit 1
    # (its own run: the frames drawn again between the timed ones would move their times)
    ./bitrain bench --scene default --path assets/$p-path.cam --size $size --frames "$FRAMES" --visibility \
      | sed -n 's/^visibility: /  visibility: /p'
    if command -v valgrind >/dev/null 2>&1; then
      out=benchmarks/out/callgrind.default.$p.$size
      valgrind --tool=callgrind --toggle-collect=bench_default_frame --callgrind-out-file=$out \
        ./bitrain bench --scene default --path assets/$p-path.cam --size $size --frames "$FRAMES" >/dev/null 2>&1
      tot=$(callgrind_annotate $out 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
      [ -n "$tot" ] && awk -v t="$tot" -v n="$FRAMES" -v p="$p" -v s="$size" \
        'BEGIN { printf "  %s %s: %.2f M instructions per frame (callgrind)\n", p, s, t / n / 1e6 }'
    fi
  done
done
