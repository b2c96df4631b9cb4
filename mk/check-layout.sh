#!/bin/sh
# The layout rules of ../shared/DESIGN.md and STYLE.md that a script can hold:
#  1. include direction platform -> raster -> core, for quoted includes too: a file in
#     core/ includes only "core/..."; one in raster/ only "core/..." or "raster/...";
#     (the <...> side, freestanding headers only, is mk/check-nofloat.sh's);
#  2. every header in core/ raster/ platform/ has an include guard (#ifndef X / #define X
#     before any other directive: no header is a multiply-included template);
#  3. files in core/ raster/ platform/ under 800 lines, functions under 200 (a function
#     runs from a line that opens with `{` in column 0 to the next `}` in column 0);
#  4. no call cycle between two files (with object files: build/obj, when there); one
#     known exception: platform/load.c picks a reader (load_*.c) and the readers call
#     the helpers load.c shares through load_internal.h.
# Prints one line per breach and exits 1 if there was any.  Usage: mk/check-layout.sh [build-dir]
B=${1:-build}
fail=0
say() { echo "layout: $*"; fail=1; }
for f in core/*.[ch] raster/*.[ch]; do
  dir=${f%%/*}
  case $dir in core) ok='core/' ;; raster) ok='(core|raster)/' ;; esac
  grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" | grep -vE "\"$ok[^\"]*\"" |
    while IFS= read -r l; do echo "layout: $f includes against platform -> raster -> core: $l"; done
done | grep . && fail=1
for h in core/*.h raster/*.h platform/*.h; do
  first=$(grep -nE '^[[:space:]]*#' "$h" | head -n 2 | sed 's/^[0-9]*:[[:space:]]*#[[:space:]]*//')
  g1=$(echo "$first" | sed -n 1p); g2=$(echo "$first" | sed -n 2p)
  n1=${g1#ifndef }; n2=${g2#define }
  case "$g1" in ifndef*) [ "$n1" = "${n2%% *}" ] || say "$h: no include guard (first directives: $g1 / $g2)" ;;
    *) say "$h: no include guard (first directive: $g1)" ;; esac
done
for f in core/*.[ch] raster/*.[ch] platform/*.[ch]; do
  n=$(wc -l < "$f"); [ "$n" -lt 800 ] || say "$f: $n lines (limit 800)"
  awk -v f="$f" '/^\{/ { s = NR } /^\}/ && s { if (NR - s + 1 >= 200) printf "layout: %s:%d: function of %d lines (limit 200)\n", f, s, NR - s + 1; s = 0 }' "$f"
done | grep . && fail=1
if [ -d "$B/obj/core" ] && command -v nm >/dev/null 2>&1; then
  tmp=${TMPDIR:-/tmp}/layout.$$; mkdir -p "$tmp"; trap 'rm -rf "$tmp"' EXIT INT TERM
  for o in "$B"/obj/core/*.o "$B"/obj/raster/*.o "$B"/obj/platform/*.o; do
    [ -f "$o" ] || continue
    nm "$o" 2>/dev/null | awk -v o="$o" '$1 ~ /^[TDBR]$/ || $2 ~ /^[TDBR]$/ { print $NF, o }' >> "$tmp/def"
    nm -u "$o" 2>/dev/null | awk -v o="$o" '{ print $NF, o }' >> "$tmp/use"
  done
  # edges user -> definer, then pairs that go both ways
  sort "$tmp/def" > "$tmp/def.s"; sort "$tmp/use" > "$tmp/use.s"
  join "$tmp/use.s" "$tmp/def.s" | awk '$2 != $3 { print $2, $3 }' | sort -u > "$tmp/edges"
  awk '{ e[$1 " " $2] = 1 } END { for (k in e) { split(k, p, " "); if ((p[2] " " p[1]) in e && p[1] < p[2] && !(p[1] ~ /platform\/load\.o$/ && p[2] ~ /platform\/load_[a-z]+\.o$/)) print "layout: call cycle between " p[1] " and " p[2] } }' "$tmp/edges" | grep . && fail=1
fi
[ "$fail" = 0 ]
