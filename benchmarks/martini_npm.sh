#!/bin/sh
# benchmarks/martini_npm.sh — the real @mapbox/martini (npm) on fuji.png padded to
# 513x513, printing its triangles and its TRUE max error at several max errors, in
# the format of bench_baselines' "martini_c" lines so the C port can be diffed
# against it.  Optional: without node/npm (or without the registry) it says
# "skipped: ..." and exits 0.  Run from the repository root:  sh benchmarks/martini_npm.sh
# The package is installed (npm ci, pinned by package-lock.json) into
# benchmarks/out/martini_npm/node_modules, which git ignores with benchmarks/out/.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  echo "skipped: node not available"; exit 0
fi
D=benchmarks/out/martini_npm
mkdir -p "$D" || exit 0
cp benchmarks/martini_npm/package.json benchmarks/martini_npm/package-lock.json \
   benchmarks/martini_npm/run.mjs "$D"/ || exit 0
if [ ! -f "$D/node_modules/@mapbox/martini/package.json" ]; then
  (cd "$D" && npm ci --no-audit --no-fund --loglevel=error >/dev/null 2>&1) ||
    { echo "skipped: npm ci @mapbox/martini failed (registry not reachable?)"; exit 0; }
fi
PNG="${BITRAIN_DATA:-../shared/data/dem}/png/fuji.png"
[ -f "$PNG" ] || { echo "skipped: $PNG not found"; exit 0; }
node "$D/run.mjs" "$PNG" 500 50 20 10 5 1 0
