#!/bin/sh
# tests/fuzz.sh [SECONDS] — `make fuzz`: build one libFuzzer harness per reader, one for the
# whole path from files on disk to a rendered band (fuzz_file), one for a saved bitree
# attached and drawn (fuzz_tree) and one for the rasteriser (tests/fuzz_*.c) with clang
# -fsanitize=fuzzer,address,undefined, seed each corpus from the real data (small crops:
# tests/data, heads of ../shared/data/dem files), and print
# one summary line per harness.  Exit 1 if any harness found a crash, a leak, a timeout
# or an out-of-memory (artifacts under $B/fuzz/artifacts).
# Time: SECONDS (default 30; make passes FUZZ_SECONDS) is the total.  The harnesses run
# one after another and each gets SECONDS / N of it (N = the number run, rounded down,
# at least 1 s), so 30 s over 10 harnesses is 3 s each; FUZZ_ONLY="file zip" runs only
# those harnesses and divides the same total among them.
# Build directory: $B, else the B=... given to make, else build.
set -u
T=${1:-30}
CC=${FUZZ_CC:-clang}
if [ -z "${B:-}" ]; then
  B=$(printf ' %s ' "${MAKEFLAGS:-}" | sed -n 's/.* B=\([^ ]*\) .*/\1/p')
fi
B=${B:-build}
D=$B/fuzz
DATA=${BITRAIN_DATA:-../shared/data/dem}
mkdir -p "$D/obj" "$D/seed" "$D/corpus" "$D/artifacts" "$D/log"

# clang with libFuzzer (Debian: clang + libclang-rt-<version>-dev)
probe() {
  printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }\n' >"$D/probe.c"
  $CC -fsanitize=fuzzer,address,undefined -o "$D/probe" "$D/probe.c" >/dev/null 2>&1
}
if ! probe; then
  v=$($CC --version 2>/dev/null | sed -n 's/.*clang version \([0-9]*\).*/\1/p' | head -n 1)
  echo "fuzz: $CC cannot build libFuzzer harnesses; installing clang${v:+ and libclang-rt-$v-dev}"
  sh mk/deps.sh clang ${v:+libclang-rt-$v-dev} || exit 1
  if ! probe; then
    echo "fuzz: still no libFuzzer; on Debian: apt-get install -y clang libclang-rt-14-dev (use your clang's version)" >&2
    exit 1
  fi
fi

PKG_CFLAGS=$(pkg-config --cflags libpng zlib)
PKG_LIBS=$(pkg-config --libs libpng zlib)
FLAGS="-std=c99 -g -O1 -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all -I. $PKG_CFLAGS"
# decompressed archives capped at 64 MB so a zip bomb is a quick refusal, not an OOM
DEFS="-DDEM_MAX_INFLATE=((size_t)64<<20)"
SRC="$(ls core/*.c raster/*.c) platform/assets.c platform/clock.c platform/err.c platform/fill.c platform/merge.c platform/pipe_threads.c platform/scene.c platform/tree_file.c platform/png_io.c $(ls platform/load*.c)"
OBJ=""
for s in $SRC; do
  o="$D/obj/$(echo "$s" | tr / _ | sed 's/\.c$/.o/')"
  $CC $FLAGS -fsanitize=fuzzer-no-link "$DEFS" -c -o "$o" "$s" || { echo "fuzz: cannot compile $s" >&2; exit 1; }
  OBJ="$OBJ $o"
done

# seeds: small pieces of the real files
S=$D/seed
rm -rf "$S"; mkdir -p "$S"
for r in hgt png asc bt tif xyz zip; do mkdir -p "$S/$r" "$D/corpus/$r"; done
head -c 7442 "$DATA/hgt/N47E009.hgt" >"$S/hgt/n47e009_61x61.hgt"         # 61x61 tile
head -c 1922 "$DATA/hgt/N50E008.hgt" >"$S/hgt/n50e008_31x31.hgt"         # 31x31 tile
cp tests/data/png/*.png "$S/png/"
cp "$DATA/asc/hugo_site.asc" "$S/asc/"
head -c 6000 "$DATA/asc/colorado_front_range.asc" >"$S/asc/colorado_head.asc"   # header + some rows
# the same grid with GeoClaw's value-first header (topotype 3): the loaders pick the
# GeoClaw reader by content, so this harness reaches it too
awk 'NR <= 6 { print $2, $1; next } { print }' "$DATA/asc/hugo_site.asc" >"$S/asc/hugo_site.tt3"
cp tests/data/bt/*.bt "$S/bt/"
cp tests/data/tif/*.tif "$S/tif/"
head -n 488 "$DATA/xyz/monai_valley_bathymetry.txt" >"$S/xyz/monai_2cols.txt"   # two whole x columns
cp tests/data/zip/*.zip "$S/zip/"
gzip -9 -n -c "$S/hgt/n47e009_61x61.hgt" >"$S/zip/n47e009_61x61.hgt.gz"
# fuzz_file: byte 0 picks the extension (tests/fuzz_file.c's table), byte 1 the split
mkdir -p "$S/file" "$D/corpus/file"
sel() { printf "\\$(printf '%03o' "$1")\\$(printf '%03o' "${4:-0}")" | cat - "$2" >"$S/file/$3"; }
sel 0 "$S/hgt/n47e009_61x61.hgt" hgt; sel 16 "$S/hgt/n47e009_61x61.hgt" hgt_two 128
sel 1 tests/data/png/ps_height_crop.png png; sel 2 tests/data/tif/ref_int16.tif tif
sel 3 tests/data/bt/crater_crop.bt bt; sel 4 "$S/asc/hugo_site.asc" asc
sel 5 "$S/xyz/monai_2cols.txt" xyz; sel 7 "$S/zip/n47e009_61x61.hgt.gz" hgtgz
sel 8 tests/data/zip/N47E009_61x61.hgt.zip hgtzip
{ printf '%s\n' '3 ncols' '2 nrows' '0 xlower' '0 ylower' '0.014 cellsize' '-9999 nodata_value'
  head -n 6 "$DATA/xyz/monai_valley_bathymetry.txt" | awk '{ print $3 }'; } >"$S/file/tt2.raw"   # GeoClaw topotype 2
sel 10 "$S/file/tt2.raw" tt2; rm -f "$S/file/tt2.raw"

# fuzz_tree: byte 0 asks for right checksums (bit 0) and header patches (bit 1), then the
# camera and three-byte patches (tests/fuzz_tree.c); the patches' bytes from a real tile
mkdir -p "$S/tree" "$D/corpus/tree"
for m in 0 1 3; do
  printf "\\$(printf '%03o' $m)\\200\\200" | cat - "$S/hgt/n50e008_31x31.hgt" | head -c 603 >"$S/tree/patch200_$m"
  printf "\\$(printf '%03o' $m)\\100\\300" | cat - "$S/hgt/n47e009_61x61.hgt" | head -c 30 >"$S/tree/patch9_$m"
done

harnesses=${FUZZ_ONLY:-$(ls tests/fuzz_*.c | sed 's/.*fuzz_\(.*\)\.c/\1/')}
n=$(echo $harnesses | wc -w)
per=$((T / n)); [ "$per" -lt 1 ] && per=1
echo "fuzz: ${T}s divided evenly among $n harnesses: ${per}s each, one after another (build dir $D)"
status=0
for h in $harnesses; do
  $CC $FLAGS -fsanitize=fuzzer "$DEFS" -o "$D/fuzz_$h" "tests/fuzz_$h.c" $OBJ $PKG_LIBS -lpthread -lm ||
    { echo "fuzz: cannot build tests/fuzz_$h.c" >&2; status=1; continue; }
  seeds="$S/$h"; [ -d "$seeds" ] || seeds=""
  mkdir -p "$D/corpus/$h"     # every harness, seeded or not (fuzz_raster has no seeds)
  log="$D/log/$h.log"
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1 \
  "$D/fuzz_$h" -max_total_time="$per" -max_len=32768 -timeout=20 -rss_limit_mb=2560 \
    -artifact_prefix="$D/artifacts/$h-" -print_final_stats=1 "$D/corpus/$h" $seeds >"$log" 2>&1
  rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1)
  if [ "$rc" = 0 ]; then
    echo "ok     fuzz_$h: ${runs:-?} runs, ${cov:-cov: ?}, corpus $(ls "$D/corpus/$h" | wc -l) inputs"
  else
    status=1
    echo "FAILED fuzz_$h (exit $rc): $(grep -m 1 -E 'ERROR|WARNING: Memory|deadly|Timeout' "$log")"
    grep -m 1 'Test unit written to' "$log" | sed 's/^/       /'
  fi
done
[ "$status" = 0 ] && echo "fuzz: all $n harnesses ran clean" || echo "fuzz: findings above (logs in $D/log)"
exit $status
