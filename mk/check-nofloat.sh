#!/bin/sh
# Prove that core/ and raster/ contain no floating point: compile every file with
# -mgeneral-regs-only (x86-64, AArch64), which makes any float/double an error,
# and also check that they include only freestanding headers.  Every C file of the
# project stays C99: GCC and clang accept C11 keywords such as _Static_assert under
# -std=c99 -pedantic-errors without a word, so they are searched for by name
# (outside comment lines).
# Usage: mk/check-nofloat.sh CC file.c...
cc=$1; shift
fail=0
arch=$($cc -dumpmachine 2>/dev/null)
# compile FILE [DEFINE] with $flag; any float or double is an error there
nofloat_cc() {
  if ! $cc -std=c99 -pedantic-errors -O2 $flag $2 -I. -c -o /dev/null "$1" 2>/tmp/nofloat.$$; then
    echo "nofloat: $1 $2 uses floating point (or fails to build with $flag):"; head -5 /tmp/nofloat.$$; fail=1
  fi
}
case "$arch" in
  x86_64*|aarch64*) flag=-mgeneral-regs-only ;;
  *) flag="" ;;
esac
for f in "$@"; do
  [ -f "$f" ] || continue
  if [ -n "$flag" ]; then
    # raster.c twice: without and with its vector pre-pass (RS_PREPASS; GCC's generic
    # vectors, lowered here to general registers)
    case "$f" in
      */raster.c) nofloat_cc "$f" -DRS_PREPASS=0; nofloat_cc "$f" -DRS_PREPASS=1 ;;
      *) nofloat_cc "$f" ;;
    esac
  fi
  bad=$(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<' "$f" | grep -vE '<(stdint|stddef|string|limits|assert)\.h>')
  if [ -n "$bad" ]; then echo "nofloat: $f includes a non-freestanding header: $bad"; fail=1; fi
done
for h in $(ls core/*.h raster/*.h 2>/dev/null); do
  bad=$(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*<' "$h" | grep -vE '<(stdint|stddef|string|limits|assert)\.h>')
  if [ -n "$bad" ]; then echo "nofloat: $h includes a non-freestanding header: $bad"; fail=1; fi
done
c11=$(grep -nE '\<_(Static_assert|Generic|Alignas|Alignof|Noreturn|Thread_local|Atomic)\>' \
      $(ls core/*.[ch] raster/*.[ch] platform/*.[ch] platform/*/*.[ch] tests/*.[ch] tests/*/*.[ch] \
         benchmarks/*.[ch] tools/*.[ch] 2>/dev/null) | grep -vE '^[^:]*:[0-9]+:[[:space:]]*(/\*|\*|//)' | head -5)
if [ -n "$c11" ]; then echo "nofloat: C11 keyword in a C99 project:"; echo "$c11"; fail=1; fi
# On x86-64 the normal build (SSE2 for raster.c's vector pre-pass) is also scanned:
# no floating-point arithmetic, comparison, conversion or x87 instruction may appear
# (the pre-pass uses integer SSE2 only: padd/psub/pmullw/pcmp/pmin/pmax/logic/moves).
case "$arch" in
  x86_64*)
    if command -v objdump >/dev/null 2>&1; then
      for f in "$@"; do
        [ -f "$f" ] || continue
        $cc -std=c99 -O2 -I. -c -o /tmp/nofloat.$$.o "$f" 2>/dev/null || continue
        bad=$(objdump -d --no-show-raw-insn /tmp/nofloat.$$.o | awk -F'\t' 'NF >= 2 { split($2, a, " "); print a[1] }' \
              | grep -E '^v?(add|sub|mul|div|sqrt|min|max|rcp|rsqrt|round|cmp|hadd|hsub|dp|fmadd|fmsub)[a-z0-9]*(ss|sd|ps|pd)$|^v?u?comis[sd]$|^v?cvt|^f[a-z]+$' | sort -u | tr '\n' ' ')
        if [ -n "$bad" ]; then echo "nofloat: $f compiles to floating-point instructions: $bad"; fail=1; fi
      done
      rm -f /tmp/nofloat.$$.o
    fi ;;
esac
rm -f /tmp/nofloat.$$
if [ -z "$flag" ]; then echo "nofloat: no -mgeneral-regs-only for $arch; only the header check ran"; fi
exit $fail
