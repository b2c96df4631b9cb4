#!/bin/sh
# benchmarks/tiles.sh — issue 20's goals "on any other 1201x1201 SRTM tile flown over at a
# few thousand metres": the terrain frame (bitrain bench --scene default, water and fog off,
# 1 px, 64-row bands) over every SRTM tile of ../shared/data/dem/hgt (N47E009 among them),
# along benchmarks/n50-steep.cam and n50-horizon.cam (3000 m up, 47 and 5 degrees down,
# 20 m a frame; positions relative to the tile's south-west corner, so each tile is flown
# over the same part of its ground), at 320x240 and 640x480 (goals 6 M and 12 M
# instructions a frame).  Instructions per frame and the selection's share (bd_select:
# selection, strip and vertices) by callgrind when valgrind is present, triangles a frame
# always.  Run from make bench (./bitrain built).  FRAMES=N (default 30) frames a path.
cd "$(dirname "$0")/.." || exit 1
FRAMES=${FRAMES:-30}
[ -x ./bitrain ] || { echo "skipped: ./bitrain not built"; exit 0; }
ls ../shared/data/dem/hgt/*.hgt >/dev/null 2>&1 || { echo "skipped: no ../shared/data/dem/hgt"; exit 0; }
mkdir -p benchmarks/out
for dem in ../shared/data/dem/hgt/*.hgt; do
  t=$(basename "$dem" .hgt)
  for p in n50-steep n50-horizon; do
    for size in 320x240 640x480; do
      # one run: under callgrind where valgrind is, else plain (its line gives the triangles)
      out=benchmarks/out/callgrind.tile.$t.$p.$size
      set -- ./bitrain bench --scene default --dem "$dem" --path benchmarks/$p.cam --size $size --frames "$FRAMES"
      if command -v valgrind >/dev/null 2>&1; then
        set -- valgrind --tool=callgrind --toggle-collect=bench_default_frame --callgrind-out-file=$out "$@"
      fi
      tris=$("$@" 2>/dev/null | sed -n 's/.*tris\/frame=\([0-9]*\).*/\1/p')
      line="  $t $p $size: $tris triangles a frame"
      if command -v valgrind >/dev/null 2>&1; then
        tot=$(callgrind_annotate $out 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
        sel=$(callgrind_annotate --inclusive=yes $out 2>/dev/null | awk '/bd_select/ {gsub(",", "", $1); print $1; exit}')
        [ -n "$tot" ] && [ -n "$sel" ] && line=$(awk -v t="$tot" -v s="$sel" -v n="$FRAMES" -v l="$line" \
          'BEGIN { printf "%s, %.2f M instructions a frame (selection, strip and vertices %.2f M)", l, t / n / 1e6, s / n / 1e6 }')
      fi
      echo "$line"
    done
  done
done
