# The test programs that need no display, built for one foreign target and linked
# statically (qemu-user runs them with no target sysroot).  tests/cross/suite.sh
# calls this with the target's compiler and the zlib/libpng of mk/cross-libs.sh:
#   make -f mk/cross.mk XCC=s390x-linux-gnu-gcc XB=build/cross/s390x XDEPS=build/cross/s390x/deps
# XFLAGS adds build-time knobs (the suite's knob runs: -DRS_PREPASS=1 ...).
# A test program needs a display when it names the SDL commands (cmd_view, cmd_run,
# cmd_bench); platform files that include SDL, directly or through view.h or sink_sdl.h,
# are left out of the library.
XCC    ?= cc
XB     ?= build/cross/host
XDEPS  ?= $(XB)/deps
XOPT   ?= -O2
XFLAGS ?=
XAR    ?= $(XCC:gcc=ar)
WARN    = -Wall -Wextra -Wshadow -Wundef -Wwrite-strings -Wdouble-promotion \
          -Wmissing-prototypes -Wstrict-prototypes -Wconversion -Wno-sign-conversion
XCFLAGS = -std=c99 $(WARN) $(XOPT) $(XFLAGS) -I. -I$(XDEPS)/include -MMD -MP

SDL_SRC  := $(shell grep -l '<SDL\|"platform/view.h"\|"platform/sink_sdl.h"' platform/*.c)
LIB_SRC  := $(sort $(wildcard core/*.c raster/*.c) $(filter-out platform/main.c $(SDL_SRC),$(wildcard platform/*.c)))
SUP_SRC  := $(sort $(wildcard tests/support/*.c)) benchmarks/peer_scene.c
DISP_TESTS := $(shell grep -l 'cmd_view\|cmd_run\|cmd_bench\|SDL\|platform/view.h\|platform/sink_sdl.h' tests/test_*.c)
TESTS    := $(sort $(filter-out $(DISP_TESTS),$(wildcard tests/test_*.c)))
LIB_OBJ  := $(LIB_SRC:%.c=$(XB)/obj/%.o)
SUP_OBJ  := $(SUP_SRC:%.c=$(XB)/obj/%.o)
BINS     := $(TESTS:tests/%.c=$(XB)/tests/%)

.SECONDARY:
.PHONY: all list
all: $(BINS)
list:
	@echo $(notdir $(BINS))

$(XB)/obj/%.o: %.c
	@mkdir -p $(@D)
	$(XCC) $(XCFLAGS) -c -o $@ $<

$(XB)/libbitrain.a: $(LIB_OBJ)
	rm -f $@ && $(XAR) rcs $@ $^

$(XB)/tests/%: tests/%.c $(SUP_OBJ) $(XB)/libbitrain.a
	@mkdir -p $(@D)
	$(XCC) $(XCFLAGS) -static -o $@ $< $(SUP_OBJ) $(XB)/libbitrain.a -L$(XDEPS)/lib -lpng -lz -lm

-include $(shell find $(XB)/obj $(XB)/tests -name '*.d' 2>/dev/null)
