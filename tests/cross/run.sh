#!/bin/sh
# Cross-architecture determinism: build tests/cross/xdet with every compiler and
# target available, run each (foreign ones under qemu-user, statically linked),
# and require byte-identical output.  Ends with "N passed, N failed".
# Targets: native gcc -O2 (reference), gcc -O0, gcc -O3, clang -O2, and, when
# the cross compilers and qemu are installed, 32-bit ARM (armhf; and built for
# Cortex-A7, which has a 32-bit divide instruction), AArch64 and 32-bit big-endian PowerPC.
set -u
dem=${BITRAIN_DATA:-../shared/data/dem}/hgt/N47E009.hgt
out=tests/out/cross
mkdir -p $out
src="tests/cross/xdet.c tests/cross/xdet_stages.c $(ls core/*.c raster/*.c 2>/dev/null)"
passed=0; failed=0
build() { # name cc flags...
  name=$1; cc=$2; shift 2
  command -v "$cc" >/dev/null 2>&1 || return 1
  "$cc" -std=c99 -I. "$@" -o $out/xdet-$name $src >$out/build-$name.log 2>&1
}
run() { # name [qemu]
  name=$1; q=${2:-}
  if [ -n "$q" ]; then command -v "$q" >/dev/null 2>&1 || return 1; fi
  $q $out/xdet-$name "$dem" >$out/$name.txt 2>$out/$name.err
}
build ref cc -O2 && run ref || { echo "cross: cannot build/run the native reference"; cat $out/build-ref.log; echo "0 passed, 1 failed"; exit 1; }
echo "reference (native cc -O2):"; sed 's/^/  /' $out/ref.txt
for spec in "gcc-O0 cc -O0" "gcc-O3 cc -O3 -funroll-loops" "clang-O2 clang -O2" \
            "armhf arm-linux-gnueabihf-gcc -O2 -static qemu-arm" \
            "armhf-a7 arm-linux-gnueabihf-gcc -O2 -mcpu=cortex-a7 -static qemu-arm" \
            "aarch64 aarch64-linux-gnu-gcc -O2 -static qemu-aarch64" \
            "ppc-be powerpc-linux-gnu-gcc -O2 -static qemu-ppc"; do
  set -- $spec
  name=$1; cc=$2; shift 2
  q=""; flags=""
  for a in "$@"; do case "$a" in qemu-*) q=$a ;; *) flags="$flags $a" ;; esac; done
  if ! command -v "$cc" >/dev/null 2>&1 || { [ -n "$q" ] && ! command -v "$q" >/dev/null 2>&1; }; then
    echo "skip   $name: $cc${q:+ or $q} not installed"; continue
  fi
  if ! build "$name" "$cc" $flags; then echo "FAILED $name: build"; tail -5 $out/build-$name.log; failed=$((failed+1)); continue; fi
  if ! run "$name" "$q"; then echo "FAILED $name: run"; tail -5 $out/$name.err; failed=$((failed+1)); continue; fi
  if cmp -s $out/ref.txt $out/$name.txt; then echo "ok     $name: identical"; passed=$((passed+1))
  else echo "FAILED $name: output differs"; diff $out/ref.txt $out/$name.txt | sed 's/^/  /'; failed=$((failed+1)); fi
done
echo "$passed passed, $failed failed"
[ $failed = 0 ]
