#!/bin/sh
# Run the whole suite: the no-floating-point check, the layout check (mk/check-layout.sh),
# every test program, the raster
# tests again with the 32-bit boards' divide-free quotients (BR_DIV64_NATIVE=0), and
# every test program again under AddressSanitizer + UndefinedBehaviorSanitizer.
# The board build (make mcu: both cores under QEMU against the desktop build).
# Then the cross-architecture probe (tests/cross/run.sh), the armhf check that a frame
# calls no 64-bit division helper (tests/cross/div64.sh), and the whole suite under
# qemu-user on the targets of TEST_CROSS (default s390x armhf; tests/cross/suite.sh).
# Each program ends with "N passed, N failed" (", N skipped" when some check could not
# run here: a package that could not be installed); we add them up and end with
# "N passed, N failed, N skipped", after a line with the wall time of each part.
B=${1:-build}
passed=0; failed=0; skipped=0
# wall time of each part, printed before the closing line ("time: ...")
# (from TEST_T0, when make test sets it, the build of the test programs included)
t_last=$(date +%s); t_start=${TEST_T0:-$t_last}; times=""
lap() { # $1 = the part that just ended
  t_now=$(date +%s); times="$times, $1 $((t_now - t_last)) s"; t_last=$t_now
}
[ -n "$TEST_T0" ] && times=", build $((t_last - TEST_T0)) s"
count() { # $1 = label, $2 = output file, $3 = exit code
  line=$(grep -aE '^[0-9]+ passed, [0-9]+ failed' "$2" | tail -n 1)
  s=0
  if [ -n "$line" ]; then
    p=${line%% passed*}; f=${line#*passed, }; f=${f%% failed*}
    case $line in *skipped*) s=${line#*failed, }; s=${s%% skipped*} ;; esac
  else p=0; f=0; fi
  if [ "$3" != 0 ] && [ "$f" = 0 ]; then f=1; fi   # crashed or exited non-zero without saying why
  passed=$((passed + p)); failed=$((failed + f)); skipped=$((skipped + s))
  if [ "$f" != 0 ]; then
    echo "FAILED $1 (exit $3):"; tail -n 30 "$2" | sed 's/^/  /'
  elif [ "$s" != 0 ]; then echo "ok     $1: $p passed, $s skipped"
  else echo "ok     $1: $p passed"; fi
  if [ "$s" != 0 ]; then grep -a '^skip\|skipped (' "$2" | sed 's/^ */  /'; fi
}
mkdir -p tests/out
log=tests/out/.log
if sh mk/check-nofloat.sh "${CC:-cc}" core/*.c raster/*.c >$log 2>&1; then
  echo "1 passed, 0 failed" >>$log; count "no floating point in core/ raster/" $log 0
else
  echo "0 passed, 1 failed" >>$log; count "no floating point in core/ raster/" $log 1
fi
if sh mk/check-layout.sh "$B" >$log 2>&1; then
  echo "1 passed, 0 failed" >>$log; count "layout: include direction, guards, file and function sizes, call cycles" $log 0
else
  echo "0 passed, 1 failed" >>$log; count "layout: include direction, guards, file and function sizes, call cycles" $log 1
fi
sh mk/check-install.sh "${MAKE:-make}" >$log 2>&1; rc=$?; count "make install into a DESTDIR + a program built against bitrain.pc" $log $rc
lap "checks"
for t in "$B"/tests/test_*; do
  [ -x "$t" ] || continue
  "$t" >$log 2>&1; rc=$?; count "$(basename "$t")" $log $rc
done
lap "tests"
for t in "$B"/div32-tests/test_*; do
  [ -x "$t" ] || continue
  "$t" >$log 2>&1; rc=$?; count "$(basename "$t") [BR_DIV64_NATIVE=0]" $log $rc
done
lap "div32 tests"
for t in "$B"/san-tests/test_*; do
  [ -x "$t" ] || continue
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1 \
    BITRAIN_SANITIZED=1 "$t" >$log 2>&1; rc=$?; count "$(basename "$t") [asan+ubsan]" $log $rc
done
lap "sanitized tests"
sh tests/cross/run.sh >$log 2>&1; rc=$?; count "cross-architecture determinism (tests/cross)" $log $rc
lap "determinism probe"
# the board build (docs/mcu.md): both cores under QEMU, each frame's checksum against the
# desktop build of the same code with the board's layouts (make mcu)
${MAKE:-make} -s mcu B="$B" >$log 2>&1; rc=$?
grep -a '^mcu: ' $log | sed 's/^/  /'
line=$(sed -n 's/^mcu: \([0-9]* passed, [0-9]* failed, [0-9]* skipped\)$/\1/p' $log); echo "$line" >>$log
count "the board build under QEMU against the desktop build (make mcu)" $log $rc
lap "make mcu"
sh tests/cross/div64.sh >$log 2>&1; rc=$?
grep -a ' path, ' $log | sed 's/^/  /'
count "no 64-bit division in a frame on armhf (tests/cross/div64.sh)" $log $rc
lap "armhf division check"
TEST_CROSS=${TEST_CROSS-s390x armhf}
if [ -n "$TEST_CROSS" ]; then
  sh tests/cross/suite.sh $TEST_CROSS >$log 2>&1; rc=$?
  grep -aE '^[a-z0-9]+: [0-9]+ passed' $log | sed 's/^/  /'
  count "whole suite under qemu-user ($TEST_CROSS)" $log $rc
  lap "foreign suites"
fi
echo "time: $(( $(date +%s) - t_start )) s${times}"
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" = 0 ]
