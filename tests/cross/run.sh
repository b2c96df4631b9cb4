#!/bin/sh
# Cross-architecture determinism: build tests/cross/xdet with every compiler and
# target available, run each (foreign ones under qemu-user, statically linked),
# and require byte-identical output.  Ends with "N passed, N failed, N skipped".
# Compilers: native gcc -O2 (reference), gcc -O0 -O3 -Os, clang -O0 -O2 -O3 -Os, and,
# when the cross compilers and qemu are installed, armhf (also for Cortex-A7, which
# has a 32-bit divide), AArch64, riscv64, i686, 32-bit big-endian PowerPC and 64-bit
# big-endian s390x.  Then every documented build-time knob setting (KNOBS below) once
# on each target of XDET_KNOB_TARGETS (default: the host, s390x and armhf: both byte
# orders and both word sizes; `make cross-test` sets all): every knob either keeps the
# pixels or is refused by #error, and a refusal fails here.  A compiler or qemu that is
# not installed counts as skipped, named.  Builds run JOBS at a time.
set -u
dem=${BITRAIN_DATA:-../shared/data/dem}/hgt/N47E009.hgt
out=tests/out/cross
JOBS=${JOBS:-2}
knob_targets=${XDET_KNOB_TARGETS:-native s390x armhf}
mkdir -p $out
rm -f $out/xdet-* $out/*.txt $out/*.err $out/build-*.log
src=$(echo tests/cross/xdet.c tests/cross/xdet_stages.c core/*.c raster/*.c)
# name compiler flags... [qemu-*]
COMPILERS="gcc-O0 cc -O0
gcc-O3 cc -O3 -funroll-loops
gcc-Os cc -Os
clang-O0 clang -O0
clang-O2 clang -O2
clang-O3 clang -O3
clang-Os clang -Os
armhf arm-linux-gnueabihf-gcc -O2 -static qemu-arm
armhf-a7 arm-linux-gnueabihf-gcc -O2 -mcpu=cortex-a7 -static qemu-arm
aarch64 aarch64-linux-gnu-gcc -O2 -static qemu-aarch64
riscv64 riscv64-linux-gnu-gcc -O2 -static qemu-riscv64
i686 i686-linux-gnu-gcc -O2 -static qemu-i386
ppc-be powerpc-linux-gnu-gcc -O2 -static qemu-ppc
s390x s390x-linux-gnu-gcc -O2 -static qemu-s390x"
# name flags: the knobs of core/config.h and raster/raster.c, each documented setting
KNOBS="prepass0 -DRS_PREPASS=0
prepass1 -DRS_PREPASS=1
prepass1-spanv0 -DRS_PREPASS=1 -DRS_SPANV=0
prepass0-spanv1 -DRS_PREPASS=0 -DRS_SPANV=1
div64-0 -DBR_DIV64_NATIVE=0
div64-1 -DBR_DIV64_NATIVE=1
rgb565-only -DRS_WITH_888=0 -DRS_WITH_Z32=0 -DRS_WITH_TEX=0 -DRS_TEX_FIELDS=0 -DRS_WITH_COUNT=0
narrow48 -DRS_NARROW=48"
target_line() { # target -> its line of COMPILERS ("native": cc -O2)
  if [ "$1" = native ]; then echo "native cc -O2"; else echo "$COMPILERS" | grep "^$1 "; fi
}
passed=0; failed=0; skipped=0
jobs=$out/jobs.txt; : >$jobs
plan() { # name cc flags... [qemu]: queue a build when the tools exist, else count a skip
  name=$1; cc=$2; shift 2
  q=""; flags=""
  for a in "$@"; do case "$a" in qemu-*) q=$a ;; *) flags="$flags $a" ;; esac; done
  if ! command -v "$cc" >/dev/null 2>&1 || { [ -n "$q" ] && ! command -v "$q" >/dev/null 2>&1; }; then
    echo "skip   $name: $cc${q:+ or $q} not installed"; skipped=$((skipped + 1)); return
  fi
  echo "$name $cc $flags" >>$jobs
  echo "$name $q" >>$out/runs.txt
}
: >$out/runs.txt
plan ref cc -O2
echo "$COMPILERS" | while read -r line; do set -- $line; plan "$@"; done >$out/plan.log
for t in $knob_targets; do
  line=$(target_line "$t") || { echo "cross: unknown knob target $t"; continue; }
  echo "$KNOBS" | while read -r kn kf; do set -- $line; n=$1; shift; plan "$n+$kn" "$@" $kf; done
done >>$out/plan.log
skipped=$(grep -c '^skip' $out/plan.log); grep '^skip' $out/plan.log
# builds, JOBS at a time (each line: name cc flags...)
xargs -P "$JOBS" -L 1 sh -c 'n=$0; c=$1; shift; "$c" -std=c99 -I. "$@" -o '"$out"'/xdet-$n '"$src"' >'"$out"'/build-$n.log 2>&1' <$jobs
run() { # name [qemu]
  ${2:-} $out/xdet-$1 "$dem" >$out/$1.txt 2>$out/$1.err
}
if ! [ -x $out/xdet-ref ] || ! run ref; then
  echo "cross: cannot build/run the native reference"; cat $out/build-ref.log; echo "0 passed, 1 failed"; exit 1
fi
echo "reference (native cc -O2):"; sed 's/^/  /' $out/ref.txt
# the RGB565-only build draws only that variant: its other frames are refused, so
# only its lines are compared
grep -v '^raster-888' $out/ref.txt >$out/ref-565.txt
while read -r name q; do
  [ "$name" = ref ] && continue
  if ! [ -x $out/xdet-$name ]; then echo "FAILED $name: build"; tail -5 $out/build-$name.log; failed=$((failed+1)); continue; fi
  if ! run "$name" "$q"; then echo "FAILED $name: run"; tail -5 $out/$name.err; failed=$((failed+1)); continue; fi
  want=$out/ref.txt; got=$out/$name.txt
  case $name in *rgb565-only) want=$out/ref-565.txt; grep -v '^raster-888' $out/$name.txt >$out/$name.565; got=$out/$name.565 ;; esac
  if cmp -s $want $got; then echo "ok     $name: identical"; passed=$((passed+1))
  else echo "FAILED $name: output differs"; diff $want $got | sed 's/^/  /'; failed=$((failed+1)); fi
done <$out/runs.txt
echo "$passed passed, $failed failed, $skipped skipped"
[ $failed = 0 ]
