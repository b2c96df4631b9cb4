#!/bin/sh
# Prints one md5 per peer-scene frame configuration (96 frames: cameras A/B, 320x240,
# 640x480, 1000x700, culling off/on, XRGB8888/RGB565, 32/16-bit depth, whole frame and
# 7-row bands), to check that a change to raster/ leaves every pixel unchanged:
#   sh mk/peer-frames.sh > before.txt; (change); sh mk/peer-frames.sh | diff before.txt -
# BITRAIN=path picks the binary (default ./bitrain).
bin=${BITRAIN:-./bitrain}
tmp=${TMPDIR:-/tmp}/peer_frames.$$
mkdir -p "$tmp" || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
for cam in A B; do
  for size in 320x240 640x480 1000x700; do
    for cull in "" --cull; do
      for fmt in rgb888 rgb565; do
        for depth in 32 16; do
          for bands in 0 7; do
            "$bin" bench --scene peer --camera $cam --size $size $cull --format $fmt --depth $depth \
              --bands $bands --frames 1 --warmup 0 -o "$tmp/f.png" >/dev/null || exit 1
            printf '%s %s %s %s %s %s %s\n' "$(md5sum < "$tmp/f.png" | cut -c1-32)" $cam $size "${cull:-nocull}" $fmt z$depth b$bands
          done
        done
      done
    done
  done
done
