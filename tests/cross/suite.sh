#!/bin/sh
# The whole test suite on foreign architectures: every test program that needs no
# display, built with Debian's cross compiler for each target (mk/cross.mk, statically
# linked against zlib and libpng built from Debian's sources by mk/cross-libs.sh) and
# run under qemu-user directly (no binfmt needed, no sysroot: static binaries).
# Usage: tests/cross/suite.sh [TARGET...]   (default: all five below)
# Prints "TARGET: N passed, N failed[, N skipped]" per target, then the total as
# "N passed, N failed, N skipped".  What cannot run because a package could not be
# installed (compiler, qemu, the zlib/libpng sources) is counted as skipped, one per
# test program, and named.
set -u
all="aarch64 armhf riscv64 s390x i686"
targets=${*:-$all}
B=${CROSS_BUILD:-build/cross}
JOBS=${JOBS:-2}
spec() { # target -> triplet qemu
  case $1 in
    aarch64) echo "aarch64-linux-gnu qemu-aarch64" ;;
    armhf) echo "arm-linux-gnueabihf qemu-arm" ;;
    riscv64) echo "riscv64-linux-gnu qemu-riscv64" ;;
    s390x) echo "s390x-linux-gnu qemu-s390x" ;;
    i686) echo "i686-linux-gnu qemu-i386" ;;
    *) return 1 ;;
  esac
}
pkgs="qemu-user dpkg-dev"
for t in $targets; do
  s=$(spec "$t") || { echo "cross: unknown target '$t' (known: $all)" >&2; exit 2; }
  set -- $s; pkgs="$pkgs gcc-$1"
done
sh mk/deps.sh --optional $pkgs

programs=$(make --no-print-directory -f mk/cross.mk list)
nprog=$(echo $programs | wc -w)
tp=0; tf=0; ts=0
for t in $targets; do
  set -- $(spec "$t"); triplet=$1; qemu=$2; cc=$triplet-gcc
  xb=$B/$t; mkdir -p "$xb/log"
  t0=$(date +%s)
  p=0; f=0; s=0; why=""
  if ! command -v "$cc" >/dev/null 2>&1; then why="$cc not installed (package gcc-$triplet)"
  elif ! command -v "$qemu" >/dev/null 2>&1; then why="$qemu not installed (package qemu-user)"
  elif ! sh mk/cross-libs.sh "$triplet" "$cc" "$xb/deps"; then why="no zlib/libpng for $triplet (see $xb/deps.log)"
  elif ! make --no-print-directory -f mk/cross.mk -j"$JOBS" XCC="$cc" XB="$xb" >"$xb/build.log" 2>&1; then
    echo "FAILED $t: build"; tail -n 15 "$xb/build.log" | sed 's/^/  /'
    echo "$t: 0 passed, 1 failed"; tf=$((tf + 1)); continue
  fi
  if [ -n "$why" ]; then
    echo "skip   $t: $why: $nprog test programs not run"
    echo "$t: 0 passed, 0 failed, $nprog skipped"; ts=$((ts + nprog)); continue
  fi
  t1=$(date +%s)
  for prog in $programs; do
    log=$xb/log/$prog.log
    BITRAIN_EMULATED=1 timeout 1800 "$qemu" "$xb/tests/$prog" >"$log" 2>&1; rc=$?
    line=$(grep -aE '^[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
    pp=0; ff=0; ss=0
    if [ -n "$line" ]; then
      pp=${line%% passed*}; ff=${line#*passed, }; ff=${ff%% failed*}
      case $line in *skipped*) ss=${line#*failed, }; ss=${ss%% skipped*} ;; esac
    fi
    if [ "$rc" != 0 ] && [ "$ff" = 0 ]; then ff=1; fi
    if [ "$ff" != 0 ]; then echo "FAILED $t $prog (exit $rc):"; tail -n 20 "$log" | sed 's/^/  /'; fi
    if [ "$ss" != 0 ]; then grep -a 'skipped (' "$log" | sed "s/^ */skip   $t $prog: /"; fi
    p=$((p + pp)); f=$((f + ff)); s=$((s + ss))
  done
  echo "  ($t: build $((t1 - t0)) s, run $(($(date +%s) - t1)) s)"
  if [ "$s" != 0 ]; then echo "$t: $p passed, $f failed, $s skipped"; else echo "$t: $p passed, $f failed"; fi
  tp=$((tp + p)); tf=$((tf + f)); ts=$((ts + s))
done
echo "$tp passed, $tf failed, $ts skipped"
[ "$tf" = 0 ]
