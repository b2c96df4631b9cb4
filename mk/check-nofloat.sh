#!/bin/sh
# Prove that core/ and raster/ contain no floating point: compile every file with
# -mgeneral-regs-only (x86-64, AArch64), which makes any float/double an error,
# and also check that they include only freestanding headers.
# Usage: mk/check-nofloat.sh CC file.c...
cc=$1; shift
fail=0
arch=$($cc -dumpmachine 2>/dev/null)
case "$arch" in
  x86_64*|aarch64*) flag=-mgeneral-regs-only ;;
  *) flag="" ;;
esac
for f in "$@"; do
  [ -f "$f" ] || continue
  if [ -n "$flag" ]; then
    if ! $cc -std=c99 -O2 $flag -I. -c -o /dev/null "$f" 2>/tmp/nofloat.$$; then
      echo "nofloat: $f uses floating point (or fails to build with $flag):"; head -5 /tmp/nofloat.$$; fail=1
    fi
  fi
  bad=$(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<' "$f" | grep -vE '<(stdint|stddef|string|limits|assert)\.h>')
  if [ -n "$bad" ]; then echo "nofloat: $f includes a non-freestanding header: $bad"; fail=1; fi
done
for h in $(ls core/*.h raster/*.h 2>/dev/null); do
  bad=$(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<' "$h" | grep -vE '<(stdint|stddef|string|limits|assert)\.h>')
  if [ -n "$bad" ]; then echo "nofloat: $h includes a non-freestanding header: $bad"; fail=1; fi
done
rm -f /tmp/nofloat.$$
if [ -z "$flag" ]; then echo "nofloat: no -mgeneral-regs-only for $arch; only the header check ran"; fi
exit $fail
