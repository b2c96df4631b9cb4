#!/bin/sh
# make bench: the board table (`bitrain bench`, with its JSON and chart in
# benchmarks/out), every benchmark program, then the side-by-side peers when their
# tools are present.  Benchmarks print figures (medians, instruction counts);
# they never fail on time.  Usage: benchmarks/run.sh BUILD_DIR
B=${1:-build}
mkdir -p benchmarks/out
echo "== bitrain bench"
./bitrain bench --json benchmarks/out/bench.json --chart benchmarks/out/bench.png || echo "(bitrain bench exited $?)"
for b in "$B"/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b" || echo "(benchmark $(basename "$b") exited $?)"
done
for s in benchmarks/*.sh; do
  case "$s" in benchmarks/run.sh) continue ;; esac
  echo "== $(basename "$s")"
  sh "$s" || echo "($(basename "$s") exited $?)"
done
