#!/bin/sh
# benchmarks/osmesa.sh — bitrain side by side with Mesa llvmpipe (OSMesa) on the peer scene
# of ../shared/bench/PEERS.md: cameras A and B at 320x240 and 640x480, single thread.
#
# Builds benchmarks/osmesa/bench_osmesa (only when pkg-config finds osmesa; otherwise prints
# "skipped: OSMesa not available" and exits 0), then for each of the four configurations runs
# llvmpipe and, when `./bitrain bench --scene peer ...` works, bitrain, interleaved in the same
# run, RUNS process runs each, and prints the median over process runs of each run's median
# ms/frame, the ratio llvmpipe/bitrain, and (with valgrind) instructions per frame.
# Figures, never a pass/fail on time.
#
# Usage: sh benchmarks/osmesa.sh            (from anywhere; works in the repo root)
# Environment knobs:
#   RUNS=5         process runs per renderer and configuration
#   FRAMES=30      timed frames per process run (after 3 warm-up frames)
#   CULL=0         1: back-face culling on for both (bench_osmesa --cull, bitrain bench --cull)
#   COLOUR=float   llvmpipe vertex colours: float (3 floats, as PEERS.md measured) or ubyte (RGBA8)
#   CALLGRIND=1    0: skip the instruction counts (valgrind --tool=callgrind, slow: ~20 s each)
#   BITRAIN=./bitrain            the bitrain binary to compare
#   BITRAIN_ARGS=                extra arguments for `bitrain bench` (e.g. --format rgb565)
#   OUT=benchmarks/out/osmesa    build and output directory (PNGs of the last frames land here)
#   DEM=../shared/data/dem/png/fuji.png   the peer scene's height map (passed to both)
set -u
cd "$(dirname "$0")/.." || exit 1
RUNS=${RUNS:-5}
FRAMES=${FRAMES:-30}
CULL=${CULL:-0}
COLOUR=${COLOUR:-float}
CALLGRIND=${CALLGRIND:-1}
BITRAIN=${BITRAIN:-./bitrain}
BITRAIN_ARGS=${BITRAIN_ARGS:-}
OUT=${OUT:-benchmarks/out/osmesa}
DEM=${DEM:-../shared/data/dem/png/fuji.png}

# llvmpipe without these re-faults its buffers every frame (PEERS.md: 70-98 ms instead of
# 11-16 ms) and, without LP_NUM_THREADS=0, rasterises on extra threads.  Both renderers run
# in the same environment.
export GLIBC_TUNABLES=glibc.malloc.mmap_threshold=33554432:glibc.malloc.trim_threshold=2147483647
export LP_NUM_THREADS=0

mkdir -p "$OUT"
sh benchmarks/osmesa/build.sh "$OUT" 2>"$OUT/build.log"
rc=$?
if [ $rc = 2 ]; then echo "skipped: OSMesa not available"; exit 0; fi
if [ $rc != 0 ]; then cat "$OUT/build.log" >&2; echo "osmesa.sh: building bench_osmesa failed" >&2; exit 1; fi
LP="$OUT/bench_osmesa"
[ -r "$DEM" ] || { echo "osmesa.sh: $DEM not found (run from the repo root next to ../shared)" >&2; exit 1; }

lp_flags="--colour $COLOUR"
br_flags="--dem $DEM $BITRAIN_ARGS"
[ "$CULL" = 1 ] && { lp_flags="$lp_flags --cull"; br_flags="$br_flags --cull"; }

# Does bitrain's peer benchmark work?  It must print a ms-per-frame figure we can parse.
# Accepted forms (first match wins): "ms/frame=12.3", "ms/frame: 12.3", "12.3 ms/frame",
# "12.3 ms per frame".
parse_ms() {
    sed -n -E 's/.*ms\/frame[=: ]+([0-9]+(\.[0-9]+)?).*/\1/p
               t
               s/.*[^0-9.]([0-9]+(\.[0-9]+)?) *ms( per frame|\/frame).*/\1/p
               s/^([0-9]+(\.[0-9]+)?) *ms( per frame|\/frame).*/\1/p' | head -n 1
}
have_bitrain=0
why_no_bitrain="$BITRAIN not found (run make first)"
if [ -x "$BITRAIN" ]; then
    probe=$("$BITRAIN" bench --scene peer --camera A --size 320x240 --frames 2 $br_flags 2>&1)
    prc=$?
    if [ $prc = 0 ] && [ -n "$(printf '%s\n' "$probe" | parse_ms)" ]; then
        have_bitrain=1
    else
        why_no_bitrain="\`$BITRAIN bench --scene peer\` is not ready (exit $prc: $(printf '%s' "$probe" | head -n 1))"
    fi
fi

median() { sort -n | awk '{ a[NR] = $1 } END { if (NR == 0) print "-"; else if (NR % 2) printf "%.2f", a[(NR + 1) / 2]; else printf "%.2f", (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }

CONFIGS="A:320x240 B:320x240 A:640x480 B:640x480"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

echo "peer scene (PEERS.md), llvmpipe: $($LP --dem "$DEM" --frames 1 --warmup 0 | sed -n 's/.*renderer="\([^"]*\)" version="\([^"]*\)".*/\1, \2/p')"
echo "runs=$RUNS frames=$FRAMES cull=$CULL colour=$COLOUR LP_NUM_THREADS=$LP_NUM_THREADS $(nproc 2>/dev/null || echo ?) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
[ $have_bitrain = 1 ] || echo "bitrain column: not measured: $why_no_bitrain"

# Timing: interleave renderers and configurations so drift hits both alike.
r=1
while [ $r -le "$RUNS" ]; do
    for c in $CONFIGS; do
        cam=${c%%:*}; size=${c#*:}
        "$LP" --dem "$DEM" --camera "$cam" --size "$size" --frames "$FRAMES" $lp_flags \
            -o "$OUT/llvmpipe_${cam}_${size}.png" >"$TMP/out" 2>&1 || { cat "$TMP/out" >&2; exit 1; }
        parse_ms <"$TMP/out" >>"$TMP/lp_$cam$size"
        if [ $have_bitrain = 1 ]; then
            png=""
            [ $r = 1 ] && png="-o $OUT/bitrain_${cam}_${size}.png"
            "$BITRAIN" bench --scene peer --camera "$cam" --size "$size" --frames "$FRAMES" $br_flags $png \
                >"$TMP/out" 2>&1 && parse_ms <"$TMP/out" >>"$TMP/br_$cam$size"
        fi
    done
    r=$((r + 1))
done

# Instructions per frame.  llvmpipe: callgrind counts only inside timed_frame() (the warm-up
# frame that JIT-compiles the shaders is excluded), divided by the timed frames.  bitrain:
# likewise inside bench_frame() (vertex transform + clear + draw); if that symbol is not
# there, (count of 1+K frames - count of 1 frame) / K, so loading and set-up cancel out.
cg_total() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 | sed -n 's/.*Collected : *\([0-9]*\).*/\1/p' | tail -n 1; }
have_cg=0
if [ "$CALLGRIND" = 1 ] && command -v valgrind >/dev/null 2>&1; then have_cg=1; fi
CGF=3
for c in $CONFIGS; do
    cam=${c%%:*}; size=${c#*:}
    lpi="-"; bri="-"
    if [ $have_cg = 1 ]; then
        n=$(cg_total --toggle-collect=timed_frame "$LP" --dem "$DEM" --camera "$cam" --size "$size" --frames $CGF --warmup 1 $lp_flags)
        [ -n "$n" ] && lpi=$(awk -v n="$n" -v f=$CGF 'BEGIN { printf "%.1f", n / f / 1e6 }')
        if [ $have_bitrain = 1 ]; then
            n=$(cg_total --toggle-collect=bench_frame "$BITRAIN" bench --scene peer --camera "$cam" --size "$size" --frames $CGF $br_flags)
            if [ -n "$n" ] && [ "$n" != 0 ]; then
                bri=$(awk -v n="$n" -v f=$CGF 'BEGIN { printf "%.1f", n / f / 1e6 }')
            else
                n1=$(cg_total "$BITRAIN" bench --scene peer --camera "$cam" --size "$size" --frames 1 $br_flags)
                nk=$(cg_total "$BITRAIN" bench --scene peer --camera "$cam" --size "$size" --frames $((1 + CGF)) $br_flags)
                [ -n "$n1" ] && [ -n "$nk" ] && bri=$(awk -v a="$n1" -v b="$nk" -v f=$CGF 'BEGIN { printf "%.1f", (b - a) / f / 1e6 }')
            fi
        fi
    fi
    echo "$lpi" >"$TMP/lpi_$cam$size"; echo "$bri" >"$TMP/bri_$cam$size"
done

# PEERS.md reference for llvmpipe (culling off; culling on: ms only).
peer_ref() {
    if [ "$CULL" = 1 ]; then
        case $1 in A320x240) echo "10.9 / -";; B320x240) echo "5.2 / -";; A640x480) echo "14.5 / -";; B640x480) echo "7.2 / -";; esac
    else
        case $1 in A320x240) echo "11.9 / 151";; B320x240) echo "10.8 / 138";; A640x480) echo "16.1 / 206";; B640x480) echo "14.9 / 187";; esac
    fi
}

echo
echo "| config | llvmpipe ms/frame | bitrain ms/frame | ratio llvmpipe/bitrain | llvmpipe Minstr/frame | bitrain Minstr/frame | llvmpipe Mtri/s | bitrain Mtri/s | bitrain Mpix/s | PEERS.md llvmpipe ms / Minstr |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for c in $CONFIGS; do
    cam=${c%%:*}; size=${c#*:}; k=$cam$size
    lp=$(median <"$TMP/lp_$k")
    br="-"; ratio="-"; brt="-"; brp="-"
    if [ -s "$TMP/br_$k" ]; then
        br=$(median <"$TMP/br_$k")
        ratio=$(awk -v a="$lp" -v b="$br" 'BEGIN { printf "%.2f", a / b }')
        brt=$(awk -v b="$br" 'BEGIN { printf "%.1f", 131072 / b / 1e3 }')
        brp=$(awk -v b="$br" -v s="$size" 'BEGIN { split(s, d, "x"); printf "%.1f", d[1] * d[2] / b / 1e3 }')
    fi
    lpt=$(awk -v b="$lp" 'BEGIN { printf "%.1f", 131072 / b / 1e3 }')
    echo "| $cam $size | $lp | $br | $ratio | $(cat "$TMP/lpi_$k") | $(cat "$TMP/bri_$k") | $lpt | $brt | $brp | $(peer_ref "$k") |"
done
echo
echo "spread over the $RUNS process runs (min..max of the per-run medians; paired = median of the"
echo "ratios of back-to-back llvmpipe/bitrain runs, the figure least disturbed by other load):"
for c in $CONFIGS; do
    cam=${c%%:*}; size=${c#*:}; k=$cam$size
    line="  $cam $size: llvmpipe $(sort -n "$TMP/lp_$k" | awk 'NR == 1 { a = $1 } { b = $1 } END { printf "%.2f..%.2f", a, b }')"
    if [ -s "$TMP/br_$k" ] && [ "$(wc -l <"$TMP/br_$k")" = "$(wc -l <"$TMP/lp_$k")" ]; then
        line="$line, bitrain $(sort -n "$TMP/br_$k" | awk 'NR == 1 { a = $1 } { b = $1 } END { printf "%.2f..%.2f", a, b }')"
        line="$line, paired ratio $(paste "$TMP/lp_$k" "$TMP/br_$k" | awk '{ print $1 / $2 }' | median)"
    fi
    echo "$line"
done
echo "ms/frame: median over $RUNS process runs of each run's median of $FRAMES frames (clear + draw + finish)."
echo "Mtri/s counts all 131,072 submitted triangles per frame; Mpix/s = frame pixels per second."
[ $have_cg = 1 ] || echo "instructions: not measured (valgrind missing or CALLGRIND=0)"
[ $have_bitrain = 1 ] || echo "bitrain column empty: $why_no_bitrain"
if [ $have_bitrain = 1 ]; then
    echo "pictures, llvmpipe vs bitrain (last frames in $OUT/{llvmpipe,bitrain}_<camera>_<size>.png):"
    for c in $CONFIGS; do
        cam=${c%%:*}; size=${c#*:}
        [ -r "$OUT/bitrain_${cam}_${size}.png" ] || continue
        echo "  $cam $size: $("$LP" --compare "$OUT/llvmpipe_${cam}_${size}.png" "$OUT/bitrain_${cam}_${size}.png")"
    done
else
    echo "last frames: $OUT/llvmpipe_<camera>_<size>.png"
fi
exit 0
