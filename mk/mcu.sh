#!/bin/sh
# mk/mcu.sh — `make mcu`: the board build (platform/board/) for Cortex-M0+ and Cortex-M3,
# run under QEMU (mps2-an385, semihosting) against the desktop build of the same code.
#   1. bakes the terrain (mcu/bake.c: a 257 x 257 crop of DEM, its hierarchy, shading and
#      the camera path mcu/board-path.cam) into build/mcu/bake_data.c;
#   2. builds and runs the desktop board main (build/mcu/bitrain-board-desktop), which
#      also checks each band's SPI stream against platform/sink_spi.c's sink; both mains
#      check each frame's checksum against the one the bake computed through the
#      product's own frame path (platform/scene.h scene_frame);
#   3. builds core/ and raster/ (an archive: only what the board main calls is linked)
#      with the board main for each core, soft float, -ffreestanding, no C library (nor
#      its headers: platform/board/include/string.h; the M0+'s 64-bit multiply is
#      platform/board/mul64.c's, not libgcc's), into
#      build/mcu/bitrain-CORE.elf with platform/board/mps2.ld (RAM MCU_RAM, flash
#      MCU_FLASH, stack MCU_STACK: the link fails when they do not fit), and fails when a
#      floating-point helper of libgcc is linked;
#   4. runs each elf under qemu-system-arm (timeout MCU_TIMEOUT seconds), compares every
#      `mcu frame N checksum` with `desktop frame N checksum`, and counts the instructions
#      with the TCG plugin benchmarks/qemu_insn.c (frames = full run - set-up-only run);
#   5. prints text, data, bss, the stack's high-water mark and instructions per frame,
#      also without spib_sum (the checksum only this test computes).
# Without arm-none-eabi-gcc the whole check is reported as skipped; without
# qemu-system-arm the runs are (exit 0 both times, the line says so).
# Environment: MCU_PATH MCU_RAM MCU_FLASH MCU_STACK MCU_TIMEOUT MCU_DEM MCU_CROP MCU_PIXEL_ERROR_Q8
#              MCU_MAX_TRI MCU_MAX_V B (build dir) CC; MCU_TOP=N also prints the N functions
#              that take the most instructions a frame on each core
set -u
B=${B:-build}
O=$B/mcu
CC=${CC:-cc}
# MCU_PATH: the board's frame path, stream (band by band from the tree,
# platform/board/board_stream.c, linked for a 64 KB board: build/mcu/bitrain-CORE.elf) or
# mesh (the product's whole-frame mesh and strip and its pixels, platform/board/board.c,
# 512K: build/mcu/bitrain-CORE-mesh.elf); unset: both, one after the other, one closing
# line for the two
if [ -z "${MCU_PATH:-}" ]; then
  mkdir -p "$O" || exit 1
  p=0 f=0 s=0
  for path in stream mesh; do
    MCU_PATH=$path sh "$0" > "$O/$path.log" 2>&1; rc=$?
    grep -v '^mcu: [0-9]* passed, [0-9]* failed, [0-9]* skipped$' "$O/$path.log"
    # the counts end its closing line (or the line that says why it was skipped); a run
    # that failed before it counts as one failure
    f0=$f
    eval "$(sed -n 's/^mcu: .*\b\([0-9][0-9]*\) passed, \([0-9][0-9]*\) failed, \([0-9][0-9]*\) skipped$/p=$((p + \1)) f=$((f + \2)) s=$((s + \3))/p' "$O/$path.log")"
    [ $rc != 0 ] && [ $f = $f0 ] && f=$((f + 1))
  done
  echo "mcu: $p passed, $f failed, $s skipped"
  [ $f = 0 ]
  exit
fi
case $MCU_PATH in
  stream) BOARD_PATH_SRC=platform/board/board_stream.c; MCU_RAM=${MCU_RAM:-64K}; MCU_STACK=${MCU_STACK:-8K}; SFX="" ;;
  mesh) BOARD_PATH_SRC=platform/board/board.c; MCU_RAM=${MCU_RAM:-512K}; MCU_STACK=${MCU_STACK:-12K}; SFX="-mesh" ;;
  *) echo "mcu: MCU_PATH must be stream or mesh"; exit 1 ;;
esac
MCU_FLASH=${MCU_FLASH:-2M}
MCU_TIMEOUT=${MCU_TIMEOUT:-300}
MCU_DEM=${MCU_DEM:-assets/N47E009.hgt.gz}
MCU_CROP=${MCU_CROP:-560 880 257}
MCU_PIXEL_ERROR_Q8=${MCU_PIXEL_ERROR_Q8:-448}
MCU_MAX_TRI=${MCU_MAX_TRI:-4096}
MCU_MAX_V=${MCU_MAX_V:-2560}
XCC=arm-none-eabi-gcc
WARN="-Wall -Wextra -Wshadow -Wundef -Wwrite-strings -Wdouble-promotion -Wmissing-prototypes -Wstrict-prototypes -Wconversion -Wno-sign-conversion"
SIZES="-DBOARD_MAX_TRI=$MCU_MAX_TRI -DBOARD_MAX_V=$MCU_MAX_V"
# the board's variants and vertex layout (core/config.h): the desktop build compiles
# core/ and raster/ with them too, so that both lay out the same RAM
LAYOUT="-DRS_WITH_888=0 -DRS_WITH_Z32=0 -DRS_WITH_TEX=0 -DRS_TEX_FIELDS=0 -DBR_INDEX16=1 -DBR_COHERENCE=0"
BOARD_SRC="$BOARD_PATH_SRC platform/board/board_scene.c platform/board/spi_band.c mcu/board_tree.c"
mkdir -p "$O" || exit 1

if ! command -v $XCC >/dev/null 2>&1; then
  echo "mcu: skipped: no $XCC (Debian: gcc-arm-none-eabi); 0 passed, 0 failed, 1 skipped"
  exit 0
fi

# ---- 1. bake (host)
$CC -std=c99 -O2 $WARN -I. $(pkg-config --cflags libpng zlib) -o "$O/bake" mcu/bake.c platform/board/spi_band.c "$B/libbitrain.a" \
  $(pkg-config --libs sdl2 libpng zlib) -lm || { echo "mcu: cannot build the bake tool"; exit 1; }
# shellcheck disable=SC2086
"$O/bake" "$MCU_DEM" $MCU_CROP mcu/board-path.cam "$O/bake_data.c.new" "$MCU_PIXEL_ERROR_Q8" || exit 1
cmp -s "$O/bake_data.c.new" "$O/bake_data.c" 2>/dev/null && rm -f "$O/bake_data.c.new" || mv "$O/bake_data.c.new" "$O/bake_data.c"

# ---- 2. desktop
# shellcheck disable=SC2086
$CC -std=c99 -O2 -g $WARN $SIZES $LAYOUT -I. $(pkg-config --cflags libpng zlib) -o "$O/bitrain-board-desktop$SFX" \
  platform/board/desktop_main.c $BOARD_SRC "$O/bake_data.c" core/*.c raster/*.c "$B/libbitrain.a" \
  $(pkg-config --libs sdl2 libpng zlib) -lm \
  || { echo "mcu: cannot build the desktop board main"; exit 1; }
"$O/bitrain-board-desktop$SFX" --mem > "$O/desktop$SFX.txt" || { cat "$O/desktop$SFX.txt"; echo "mcu: the desktop board main failed"; exit 1; }
arena=$(awk '/arena total/ { print $(NF - 1) }' "$O/desktop$SFX.txt")
grep 'frame 0:' "$O/desktop$SFX.txt"

# ---- 3. board builds
have_qemu=1
command -v qemu-system-arm >/dev/null 2>&1 || have_qemu=0
plugin=""
if [ $have_qemu = 1 ] && $CC -std=c99 -O2 $WARN -shared -fPIC -fvisibility=hidden -o "$O/qemu_insn.so" benchmarks/qemu_insn.c 2>/dev/null; then
  plugin="$O/qemu_insn.so"
fi
pass=0 fail=0 skip=0 summary=""
qrun() {  # elf out [arg]: qemu with semihosting, the plugin when there is one
  cfg="enable=on,target=native,arg=bitrain-board"
  [ -n "${3:-}" ] && cfg="$cfg,arg=$3"
  timeout "$MCU_TIMEOUT" qemu-system-arm -M mps2-an385 -nographic -monitor none -serial none \
    -semihosting-config "$cfg" -kernel "$1" ${plugin:+-plugin "$plugin,out=$2.insn"} > "$2" 2>&1
}
fn_table() {  # elf dir frames: instructions a frame by function (full run - set-up run), most first
  arm-none-eabi-nm -n --radix=d "$1" | awk '$2 ~ /^[tTwW]$/ { print "S", $1 + 0, $3 }' > "$2/syms"
  awk -v n="$3" '
    function hex(s,  v, i) { v = 0; for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789abcdef", substr(tolower(s), i, 1)) - 1; return v }
    $1 == "S" { a[++ns] = $2 + 0; nm[ns] = $3; next }
    $1 == "total" { f++; next }
    { x = hex($1); lo = 1; hi = ns; while (lo < hi) { m = int((lo + hi + 1) / 2); if (a[m] <= x) lo = m; else hi = m - 1 }
      c[nm[lo]] += (f == 1 ? 1 : -1) * $2 * $3 }
    END { for (k in c) if (c[k] != 0) printf "%12d %s\n", c[k] / n, k }' "$2/syms" "$2/run.txt.insn" "$2/init.txt.insn" |
    sort -rn
}
for core in m0plus m3; do
  case $core in m0plus) cpu=cortex-m0plus narrow=48 ;; m3) cpu=cortex-m3 narrow=4 ;; esac
  d=$O/$core$SFX od=$O/$core/obj   # the runs' files per path, the objects shared
  mkdir -p "$d" "$od"
  # -fbuiltin after -ffreestanding: fixed-size memcpy/memset (raster.c's 8-byte stores)
  # are expanded inline as on a hosted build; libc_min.c itself is built without it
  # (a loop there must not become a call to the function it is in)
  # platform/board/include: the board's own <string.h> (no C library's headers needed)
  # BR_COHERENCE=0: the decision memo holds one frame's decisions, twice as many in its
  # bytes (the same meshes)
  # RS_NARROW: general triangles up to this many columns wide find their row spans by
  # stepping the edge functions (in 32 bits for small ones, raster_general.h); wider
  # ones by three divisions a row: 32-bit `/` on the M3 (one instruction), reciprocals
  # in 64-bit arithmetic on the M0+, which has no divide (the same pixels either way;
  # core/config.h).  The widths are each core's fastest on the board path.
  XFLAGS="-std=c99 $WARN -O2 -g -mthumb -mcpu=$cpu -mfloat-abi=soft -ffreestanding -fbuiltin -ffunction-sections -fdata-sections \
    -isystem platform/board/include \
    $LAYOUT -DRS_NARROW=$narrow $SIZES -I."
  objs="" ok=1
  for f in core/*.c raster/*.c; do
    o=$od/$(echo "$f" | tr / _ | sed 's/\.c$/.o/')
    if [ ! -f "$o" ] || [ "$f" -nt "$o" ] || [ mk/mcu.sh -nt "$o" ] || [ -n "$(find core raster -name '*.h' -newer "$o" 2>/dev/null | head -1)" ]; then
      # shellcheck disable=SC2086
      $XCC $XFLAGS -c -o "$o" "$f" || { ok=0; break; }
    fi
    objs="$objs $o"
  done
  [ $ok = 1 ] || { echo "mcu: $core$SFX: core/ or raster/ does not build"; fail=$((fail + 1)); continue; }
  rm -f "$d/libbitrain.a"; arm-none-eabi-ar rcs "$d/libbitrain.a" $objs
  elf=$O/bitrain-$core$SFX.elf
  # shellcheck disable=SC2086
  $XCC $XFLAGS -fno-builtin -fno-tree-loop-distribute-patterns -c -o "$d/libc_min.o" platform/board/libc_min.c || { fail=$((fail + 1)); continue; }
  # shellcheck disable=SC2086
  $XCC $XFLAGS -c -o "$d/mul64.o" platform/board/mul64.c || { fail=$((fail + 1)); continue; }
  # shellcheck disable=SC2086
  if ! $XCC $XFLAGS -DBOARD_ARENA="$arena" -nostdlib -nostartfiles -T platform/board/mps2.ld \
       -Wl,--defsym=BOARD_RAM="$MCU_RAM" -Wl,--defsym=BOARD_FLASH="$MCU_FLASH" -Wl,--defsym=BOARD_STACK="$MCU_STACK" \
       -Wl,--gc-sections -Wl,-Map="$d/map.txt" -o "$elf" platform/board/mcu_main.c "$d/libc_min.o" "$d/mul64.o" $BOARD_SRC \
       "$O/bake_data.c" "$d/libbitrain.a" -lgcc; then
    echo "mcu: $core$SFX: link failed (RAM $MCU_RAM, flash $MCU_FLASH, stack $MCU_STACK)"; fail=$((fail + 1)); continue
  fi
  fl=$(arm-none-eabi-nm "$elf" | awk '{ print $NF }' | grep -E '^__aeabi_[fd]|^__(add|sub|mul|div|neg|cmp|eq|ne|lt|le|gt|ge|unord|fix|fixuns|float|floatun|extend|trunc)[sdtx]f|^__aeabi_[il]2[fd]|^__aeabi_ui2[fd]|^__aeabi_ul2[fd]' | tr '\n' ' ')
  if [ -n "$fl" ]; then echo "mcu: $core$SFX: floating-point helpers linked: $fl"; fail=$((fail + 1)); continue; fi
  eval "$(arm-none-eabi-size -A "$elf" | awk '$1 == ".text" { t = $2 } $1 == ".data" { d = $2 } $1 == ".bss" { b = $2 } $1 == ".stack" { s = $2 } $1 == ".ARM.exidx" { x = $2 } END { printf "text=%d data=%d bss=%d stk=%d\n", t + x, d, b, s }')"
  ram=$((data + bss + stk))
  baked=$(arm-none-eabi-nm -S --radix=d "$elf" | awk '$NF ~ /^bake(_z|_tree|_lvl|_ztab)?$/ { s += $2 } END { print s + 0 }')
  line="$core$SFX: text $text (code $((text - baked)), baked terrain $baked), data $data, bss $bss"
  if [ $have_qemu = 0 ]; then
    echo "mcu: $line; run skipped: no qemu-system-arm"; skip=$((skip + 1)); summary="$summary
$line"; continue
  fi
  qrun "$elf" "$d/run.txt"; rc=$?
  grep -q 'mcu stack' "$d/run.txt" || rc=1
  sed -n 's/^mcu frame \([0-9]*\) checksum: /\1 /p' "$d/run.txt" > "$d/sums"
  sed -n 's/^desktop frame \([0-9]*\) checksum: /\1 /p' "$O/desktop$SFX.txt" > "$O/desktop$SFX.sums"
  stack=$(sed -n 's/^mcu stack: \([0-9]*\) of.*/\1/p' "$d/run.txt")
  if [ $rc != 0 ] || [ ! -s "$d/sums" ] || ! cmp -s "$d/sums" "$O/desktop$SFX.sums"; then
    echo "mcu: $core$SFX: FAILED (qemu exit $rc); the board's and the desktop's checksums:"
    paste "$d/sums" "$O/desktop$SFX.sums" 2>/dev/null | head -12
    tail -5 "$d/run.txt"
    fail=$((fail + 1)); continue
  fi
  ipf="-"
  if [ -n "$plugin" ] && [ -f "$d/run.txt.insn" ] && qrun "$elf" "$d/init.txt" init; then
    n=$(wc -l < "$d/sums")
    ipf=$(awk -v n="$n" 'FNR == 1 && $1 == "total" { t[++k] = $2 } END { if (k == 2 && n > 0) printf "%d", (t[1] - t[2]) / n; else print "-" }' \
      "$d/run.txt.insn" "$d/init.txt.insn")
  fi
  # the frame's count includes spib_sum, the checksum only this test computes (a panel
  # needs the stream, not its sum): its share is said beside it
  own=""
  if [ "$ipf" != "-" ]; then
    fn_table "$elf" "$d" "$n" > "$d/functions.txt"
    sum_ipf=$(awk '$2 == "spib_sum" { s = $1 } END { print s + 0 }' "$d/functions.txt")
    own=" ($((ipf - sum_ipf)) without the test's checksum)"
  fi
  line="$line, stack $stack (of $MCU_STACK), $ipf instructions/frame$own"
  echo "mcu: $line; $(wc -l < "$d/sums") checksums match the desktop's"
  [ "${MCU_TOP:-0}" -gt 0 ] && [ "$ipf" != "-" ] && head -n "$MCU_TOP" "$d/functions.txt" | sed "s/^/mcu:   /"
  summary="$summary
$line"; pass=$((pass + 1))
done
[ -n "${ram:-}" ] && echo "mcu: RAM ($MCU_PATH path): data + bss + stack = $ram bytes (arena $arena); linked for $MCU_RAM; the 64 KB goal: $( [ "$ram" -le 65536 ] && echo met || echo "not met")"
echo "mcu: $pass passed, $fail failed, $skip skipped"
[ $fail = 0 ]
