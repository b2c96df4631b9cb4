# bitrain — terrain on boards with no GPU.
# The only two commands a user needs: `make run` and `make test`.
# Other targets: all (default: ./bitrain + build/libbitrain.a), install, bench, fuzz, mcu, clean.
#
# Sources are found by folder, so adding a module is adding its .c/.h pair:
#   core/*.c raster/*.c platform/*.c  -> build/libbitrain.a (platform/main.c -> ./bitrain)
#   tests/test_*.c                    -> one test program each (tests/run.sh runs them)
#   benchmarks/bench_*.c              -> one benchmark program each (make bench)
#   tests/fuzz_*.c                    -> one libFuzzer harness each (make fuzz, clang)

# The first rule below is not `all` (the ISA flag rules come first): name the goal.
.DEFAULT_GOAL := all

CC      ?= cc
ifeq ($(origin CC),default)
CC      = cc
endif
PKGS    = sdl2 libpng zlib
OPT     ?= -O2
# The warning set of ../shared/STYLE.md (Lua's).  -Wconversion in C also turns on
# -Wsign-conversion; we keep the narrowing half and drop the sign half, which flags
# every size_t/int mix without catching real bugs in this code base.
WARN    = -Wall -Wextra -Wshadow -Wundef -Wwrite-strings -Wdouble-promotion \
          -Wmissing-prototypes -Wstrict-prototypes -Wconversion -Wno-sign-conversion
ifeq ($(CI),true)
WARN   += -Werror
endif
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null)
CFLAGS  ?= $(OPT) -g
ALL_CFLAGS = -std=c99 $(WARN) $(CFLAGS) -I. -MMD -MP
LDLIBS  = $(PKG_LIBS) -lm

B       = build
CORE_SRC   = $(sort $(wildcard core/*.c))
RASTER_SRC = $(sort $(wildcard raster/*.c))
# the program's own sources (not in libbitrain.a): main, and `bitrain bench` with the
# benchmark scene it draws (benchmarks/peer_scene.c, also linked into tests and benches)
PROG_SRC   = platform/main.c platform/cmd_bench.c platform/bench_board.c benchmarks/peer_scene.c
PLAT_SRC   = $(sort $(filter-out $(PROG_SRC),$(wildcard platform/*.c)))
LIB_SRC    = $(CORE_SRC) $(RASTER_SRC) $(PLAT_SRC)
TEST_SRC   = $(sort $(wildcard tests/test_*.c))
BENCH_SRC  = $(sort $(wildcard benchmarks/bench_*.c))
SUPPORT_SRC= $(sort $(wildcard tests/support/*.c)) benchmarks/peer_scene.c

LIB_OBJ    = $(LIB_SRC:%.c=$(B)/obj/%.o)
# x86-64: the drawing code (raster.c, xform.c) and the water's passes and post hook
# (water.c, water_pass.c) a second time for x86-64-v3 CPUs (AVX2, BMI2), chosen at run
# time by raster/isa.c (the water's: rw_post and water_run, by rs_isa); when the
# compiler can (gcc >= 12: the -march level and __builtin_cpu_supports("x86-64-v3")).
# ISA_V3=0 leaves it out.
ISA_V3    ?= $(shell $(CC) -dumpmachine 2>/dev/null | grep -q '^x86_64' && printf 'int main(void){__builtin_cpu_init();return __builtin_cpu_supports("x86-64-v3");}\n' | $(CC) -march=x86-64-v3 -x c -o /dev/null - 2>/dev/null && echo 1)
ifeq ($(ISA_V3),1)
LIB_OBJ   += $(B)/obj/raster/raster_v3.o $(B)/obj/raster/xform_v3.o $(B)/obj/raster/water_v3.o \
             $(B)/obj/raster/water_pass_v3.o
$(B)/obj/raster/raster.o $(B)/obj/raster/xform.o $(B)/obj/raster/water.o $(B)/obj/raster/water_pass.o \
$(B)/obj/raster/isa.o: ISA_FLAGS = -DRS_ISA_DISPATCH=1
endif
# the objects whose symbols depend on ISA_V3 are rebuilt when it changes (the file
# is rewritten only then)
$(B)/obj/raster/raster.o $(B)/obj/raster/xform.o $(B)/obj/raster/water.o $(B)/obj/raster/water_pass.o \
$(B)/obj/raster/isa.o: $(B)/isa_v3.flag
$(B)/isa_v3.flag: FORCE
	@mkdir -p $(@D); echo '$(ISA_V3)' | cmp -s - $@ || echo '$(ISA_V3)' > $@
TEST_BIN   = $(TEST_SRC:tests/%.c=$(B)/tests/%)
BENCH_BIN  = $(BENCH_SRC:benchmarks/%.c=$(B)/bench/%)
SUPPORT_OBJ= $(SUPPORT_SRC:%.c=$(B)/obj/%.o)

# Sanitizer build of the same library and tests (make test runs both).
SAN_FLAGS  = -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
SAN_LIB_OBJ= $(LIB_SRC:%.c=$(B)/san/%.o)
SAN_SUP_OBJ= $(SUPPORT_SRC:%.c=$(B)/san/%.o)
SAN_TEST_BIN = $(TEST_SRC:tests/%.c=$(B)/san-tests/%)

# The raster and water tests again with the divide-free quotients of 32-bit boards
# (core/config.h BR_DIV64_NATIVE = 0), which must give the same bytes as `/`, and
# with fx_inv40's branch for targets with a 32-bit divide (FX_TEST_IDIV stands in
# for __ARM_FEATURE_IDIV; test_fx checks that branch against `/` for every a) and
# raster.c's other 32-bit-target choices (RS_TEST_32BIT: narrow types, ctz64; RS_PREPASS=0:
# the per-pair strip code of targets without vector registers, see raster.c).
DIV32_FLAGS = $(OPT) -g -DBR_DIV64_NATIVE=0 -DFX_TEST_IDIV -DRS_TEST_32BIT -DRS_PREPASS=0
DIV32_LIB_OBJ = $(LIB_SRC:%.c=$(B)/div32/%.o)
DIV32_SUP_OBJ = $(SUPPORT_SRC:%.c=$(B)/div32/%.o)
DIV32_TEST_BIN = $(B)/div32-tests/test_raster $(B)/div32-tests/test_raster_render $(B)/div32-tests/test_fx \
                 $(B)/div32-tests/test_framecost $(B)/div32-tests/test_terrain $(B)/div32-tests/test_water \
                 $(B)/div32-tests/test_water_setup $(B)/div32-tests/test_coherence $(B)/div32-tests/test_stream

.SECONDARY:
.PHONY: all run test test-fast cross-test bench fuzz clean deps check-nofloat install mcu FORCE
all: deps bitrain $(B)/libbitrain.a

deps:
	@sh mk/deps.sh

# pkg-config is asked again here: deps may have just installed the packages.
$(B)/bitrain: $(PROG_SRC:%.c=$(B)/obj/%.o) $(B)/libbitrain.a
	$(CC) $(ALL_CFLAGS) -o $@ $^ $(shell pkg-config --libs $(PKGS)) -lm

bitrain: $(B)/bitrain
	cp $< $@

$(B)/libbitrain.a: $(LIB_OBJ)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

$(B)/obj/raster/%_v3.o: raster/%.c
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -march=x86-64-v3 -DRS_BUILD_V3 -c -o $@ $<

# `| deps`: with -j the packages are installed before the first compile, not beside it.
$(B)/obj/%.o: %.c | deps
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(ISA_FLAGS) $(if $(filter platform/% tests/% benchmarks/%,$<),$(shell pkg-config --cflags $(PKGS))) -c -o $@ $<

$(B)/tests/%: tests/%.c $(SUPPORT_OBJ) $(B)/libbitrain.a
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(shell pkg-config --cflags $(PKGS)) -o $@ $< $(SUPPORT_OBJ) $(B)/libbitrain.a $(shell pkg-config --libs $(PKGS)) -lm

$(B)/bench/%: benchmarks/%.c $(SUPPORT_OBJ) $(B)/libbitrain.a
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(shell pkg-config --cflags $(PKGS)) -o $@ $< $(SUPPORT_OBJ) $(B)/libbitrain.a $(shell pkg-config --libs $(PKGS)) -lm

$(B)/san/%.o: %.c
	@mkdir -p $(@D)
	$(CC) -std=c99 $(WARN) $(SAN_FLAGS) -I. -MMD -MP $(shell pkg-config --cflags $(PKGS)) -c -o $@ $<

$(B)/libbitrain-san.a: $(SAN_LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(B)/san-tests/%: tests/%.c $(SAN_SUP_OBJ) $(B)/libbitrain-san.a
	@mkdir -p $(@D)
	$(CC) -std=c99 $(WARN) $(SAN_FLAGS) -I. $(shell pkg-config --cflags $(PKGS)) -o $@ $< $(SAN_SUP_OBJ) $(B)/libbitrain-san.a $(shell pkg-config --libs $(PKGS)) -lm

$(B)/div32/%.o: %.c
	@mkdir -p $(@D)
	$(CC) -std=c99 $(WARN) $(DIV32_FLAGS) -I. -MMD -MP $(shell pkg-config --cflags $(PKGS)) -c -o $@ $<

$(B)/libbitrain-div32.a: $(DIV32_LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(B)/div32-tests/%: tests/%.c $(DIV32_SUP_OBJ) $(B)/libbitrain-div32.a
	@mkdir -p $(@D)
	$(CC) -std=c99 $(WARN) $(DIV32_FLAGS) -I. $(shell pkg-config --cflags $(PKGS)) -o $@ $< $(DIV32_SUP_OBJ) $(B)/libbitrain-div32.a $(shell pkg-config --libs $(PKGS)) -lm

# core/ and raster/ must not use floating point at all.  On x86-64 and AArch64,
# -mgeneral-regs-only makes the compiler refuse any float or double; elsewhere we
# fall back to scanning the objects for soft-float helper symbols.
check-nofloat:
	@sh mk/check-nofloat.sh $(CC) $(CORE_SRC) $(RASTER_SRC)

# The default terrain: Lake Constance (SRTM3 N47E009), shipped zlib-compressed.
RUN_DEM ?= assets/N47E009.hgt.gz
run: all
	./bitrain run $(RUN_DEM)

# What the suite adds beyond the build: clang (second compiler), and the cross
# compilers + qemu-user that run the determinism probe on 32-bit ARM, AArch64, riscv64,
# i686, s390x and big-endian PowerPC, and the whole suite on TEST_CROSS (s390x: 64-bit
# big-endian, armhf: 32-bit; tests/cross/suite.sh, with zlib and libpng built from
# Debian's source packages: dpkg-dev unpacks them).  Optional: without them those checks
# are counted as skipped.  TEST_CROSS= leaves the cross suites out.
TEST_PKGS = clang qemu-user dpkg-dev gcc-arm-linux-gnueabihf gcc-aarch64-linux-gnu gcc-powerpc-linux-gnu \
            gcc-s390x-linux-gnu gcc-riscv64-linux-gnu gcc-i686-linux-gnu
TEST_CROSS ?= s390x armhf
test: deps
	@sh mk/deps.sh --optional $(TEST_PKGS)
	@t0=$$(date +%s); $(MAKE) --no-print-directory bitrain $(TEST_BIN) $(SAN_TEST_BIN) $(DIV32_TEST_BIN) && \
	 TEST_T0=$$t0 TEST_CROSS="$(TEST_CROSS)" sh tests/run.sh $(B)

# The whole suite (every test program without a display) on five foreign targets
# under qemu-user, and the determinism probe with every knob setting on each of them
# (tests/cross/run.sh, tests/cross/suite.sh; build/cross/TARGET/).
CROSS_TARGETS ?= aarch64 armhf riscv64 s390x i686
CROSS_PKGS = clang qemu-user dpkg-dev gcc-aarch64-linux-gnu gcc-arm-linux-gnueabihf gcc-riscv64-linux-gnu \
             gcc-s390x-linux-gnu gcc-i686-linux-gnu
cross-test: deps
	@sh mk/deps.sh --optional $(CROSS_PKGS)
	@XDET_KNOB_TARGETS="native $(CROSS_TARGETS)" sh tests/cross/run.sh; p=$$?; \
	 sh tests/cross/suite.sh $(CROSS_TARGETS) && exit $$p

# The board build (docs/mcu.md): core/ and raster/ with the bare-metal main of
# platform/board/ for Cortex-M0+ and Cortex-M3, run under qemu-system-arm against the
# desktop build of the same code (mk/mcu.sh; MCU_RAM= MCU_STACK= MCU_FLASH= size the link).
# Without the cross compiler it is reported as skipped.
MCU_PKGS = gcc-arm-none-eabi qemu-system-arm
mcu: deps $(B)/libbitrain.a
	@sh mk/deps.sh --optional $(MCU_PKGS)
	@B=$(B) CC="$(CC)" sh mk/mcu.sh

# make install [PREFIX=/usr/local] [DESTDIR=]: the program, libbitrain.a, the public
# headers under include/bitrain/ (so that "core/hf.h" etc. resolve with the .pc's
# -I), bitrain.pc, and assets/ as DATADIR (PREFIX/share/bitrain).  The installed
# program and library have platform/assets.c compiled again with that DATADIR
# (ASSET_DATADIR; build/install/), so both find the data there from any directory and
# any BINDIR (platform/assets.h).
# Internal headers (*_int.h, *_internal.h, core/bt_em.h, the raster's own raster_*.h,
# platform/cmd.h) stay out.
VERSION ?= 0.1
PREFIX  ?= /usr/local
BINDIR  ?= $(PREFIX)/bin
LIBDIR  ?= $(PREFIX)/lib
INCDIR  ?= $(PREFIX)/include
DATADIR ?= $(PREFIX)/share/bitrain
ASSET_FILES = $(wildcard assets/*.gz assets/*.cam) assets/README.md
PUB_HDR  = $(sort $(filter-out %_int.h %_internal.h core/bt_em.h raster/raster_%.h platform/cmd.h platform/peer_scene.h,\
             $(wildcard core/*.h raster/*.h platform/*.h)))
INST = $(B)/install
install: bitrain $(B)/libbitrain.a
	@mkdir -p $(INST)
	$(CC) $(ALL_CFLAGS) $(ISA_FLAGS) $(shell pkg-config --cflags $(PKGS)) -DASSET_DATADIR='"$(DATADIR)"' -c -o $(INST)/assets.o platform/assets.c
	cp $(B)/libbitrain.a $(INST)/libbitrain.a && ar rs $(INST)/libbitrain.a $(INST)/assets.o
	$(CC) $(ALL_CFLAGS) -o $(INST)/bitrain $(PROG_SRC:%.c=$(B)/obj/%.o) $(INST)/libbitrain.a \
	    $(shell pkg-config --libs $(PKGS)) -lm
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(LIBDIR)/pkgconfig $(addprefix $(DESTDIR)$(INCDIR)/bitrain/,core raster platform)
	install -m 755 $(INST)/bitrain $(DESTDIR)$(BINDIR)/bitrain
	install -m 644 $(INST)/libbitrain.a $(DESTDIR)$(LIBDIR)/libbitrain.a
	install -d $(DESTDIR)$(DATADIR)
	install -m 644 $(ASSET_FILES) $(DESTDIR)$(DATADIR)/
	for h in $(PUB_HDR); do install -m 644 $$h $(DESTDIR)$(INCDIR)/bitrain/$$h || exit 1; done
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' -e 's|@INCDIR@|$(INCDIR)|' \
	    -e 's|@VERSION@|$(VERSION)|' mk/bitrain.pc.in > $(DESTDIR)$(LIBDIR)/pkgconfig/bitrain.pc

# Benchmarks print figures; they never fail on time.
bench: all $(BENCH_BIN)
	@sh benchmarks/run.sh $(B)

FUZZ_SECONDS ?= 30
fuzz: deps
	@sh tests/fuzz.sh $(FUZZ_SECONDS)

clean:
	rm -rf $(B) bitrain tests/out benchmarks/out out

-include $(shell find $(B) -name '*.d' 2>/dev/null)
