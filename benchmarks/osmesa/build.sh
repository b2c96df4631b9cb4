#!/bin/sh
# Build the llvmpipe side of the side-by-side benchmark (benchmarks/osmesa.sh).
# Benchmark-only dependency: OSMesa (Debian libosmesa6-dev) is NOT part of the main
# Makefile or the library.  Exit status 2 (and a message) when OSMesa is not available.
# Usage: benchmarks/osmesa/build.sh [OUT_DIR]   (default build-osmesa; binary OUT_DIR/bench_osmesa)
set -eu
out=${1:-build-osmesa}
here=$(dirname "$0")
if ! pkg-config --exists osmesa libpng 2>/dev/null; then
  echo "skipped: OSMesa not available (install libosmesa6-dev)" >&2
  exit 2
fi
mkdir -p "$out"
# -O2 like the project; -ffp-contract=off so the scene's doubles round exactly as in peer_scene.py.
# peer_scene.c builds the frames with the fixed-point camera (core/cam.c, core/fx.c).
${CC:-cc} -std=c99 -O2 -g -ffp-contract=off -Wall -Wextra -Wshadow -Wdouble-promotion -Wconversion -Wno-sign-conversion \
  -I"$here/../.." $(pkg-config --cflags osmesa libpng) -o "$out/bench_osmesa" "$here/bench_osmesa.c" \
  "$here/../../benchmarks/peer_scene.c" "$here/../../platform/png_io.c" "$here/../../platform/err.c" \
  "$here/../../core/cam.c" "$here/../../core/fx.c" \
  $(pkg-config --libs osmesa libpng) -lm
