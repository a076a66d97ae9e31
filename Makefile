# celscan - one non-recursive Makefile.
#
# Host programs go to build/host/, sanitizer builds to build/asan/, and
# firmware images to build/<board>/. Only core/ is built freestanding; host
# code links libc, cJSON and libpng. `make V=1` shows the commands.
#
#   make            host programs: celsim, celc, celfw
#   make demo       render the demo scene and animation with the host simulator
#   make test       every test: unit, image, sanitizers, freestanding checks
#   make deps       install the Debian packages the build needs (as root)

Q := $(if $(V),,@)
CC ?= cc
BUILD := build
HOST := $(BUILD)/host
ASAN := $(BUILD)/asan

# Floating point must give the same bytes on every target: no FMA contraction,
# no errno-setting math calls, no library math.
FP_FLAGS := -ffp-contract=off -fno-math-errno -fno-trapping-math
WARN := -Wall -Wextra -Wshadow -Wconversion -Wno-sign-conversion -Wmissing-prototypes \
        -Wstrict-prototypes -Wdouble-promotion -Wundef
CORE_FREESTANDING := -ffreestanding -fno-builtin -fno-tree-loop-distribute-patterns \
        -fno-stack-protector
OPT ?= -O2

CORE_SRC := $(sort $(wildcard core/*.c))
CORE_HDR := $(wildcard core/*.h)

PKGS := libcjson libpng
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS = $(shell pkg-config --libs $(PKGS) 2>/dev/null)

HOST_CFLAGS := -std=c11 $(OPT) -g $(FP_FLAGS) -Wall -Wextra -Wshadow -Wmissing-prototypes \
        -Icore -Ihal -Ihost-sim -Itools -D_POSIX_C_SOURCE=200809L -MMD -MP
CORE_CFLAGS := -std=c11 $(OPT) -g $(FP_FLAGS) $(WARN) $(CORE_FREESTANDING) -Icore -MMD -MP

# Objects also depend on a record of the flags they are compiled with,
# build/flags/NAME, which is rewritten (so newer) only when the flags
# change: `make OPT=-O0`, an edited flag or a file moved between the
# firmware's size- and speed-optimised lists rebuilds what it affects,
# where the sources alone would leave stale objects that link silently.
# $(eval $(call flags_record,NAME,FLAGS)) writes it when make reads this.
FLAGS_DIR := $(BUILD)/flags
$(shell mkdir -p $(FLAGS_DIR))
define flags_record
ifneq ($$(file <$(FLAGS_DIR)/$(1)),$(strip $(2)))
$$(file >$(FLAGS_DIR)/$(1),$(strip $(2)))
endif
endef
# A record removed while make runs (make clean) only forces a rebuild.
$(FLAGS_DIR)/%: ;

.PHONY: all deps demo demo-all test test-all check-core clean
# The default goal; its prerequisites are listed after the fragments.
all:

# The entry points set up the machine first, then run in a fresh make so
# that pkg-config sees what was just installed.
deps:
	$(Q)tools/install-deps.sh

# make test builds on every core (TEST_JOBS, default the machine's count):
# the programs test-all needs, and what each part's target needs, since
# tests/run.sh runs those targets' makes under this one's job server. The
# tests themselves run one at a time, so timing and the loopback servers
# are as with -j1.
TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 1)
test:
	$(Q)tools/install-deps.sh
	$(Q)$(MAKE) --no-print-directory -j$(TEST_JOBS) test-all

demo:
	$(Q)tools/install-deps.sh
	$(Q)$(MAKE) --no-print-directory demo-all

# ------------------------------------------------------------------ core
$(eval $(call flags_record,host-core,$(CC) $(CORE_CFLAGS)))
$(HOST)/core/%.o: core/%.c $(CORE_HDR) $(FLAGS_DIR)/host-core
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CORE_CFLAGS) -c $< -o $@

CORE_OBJ := $(patsubst core/%.c,$(HOST)/core/%.o,$(CORE_SRC))
$(HOST)/libcelscan.a: $(CORE_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

# The core must stand alone on every target: cross-compile it for a
# Cortex-M4F and for RV32IMAC and check its symbols on the host and ARM.
ARM_CC := arm-none-eabi-gcc
ARM_CORE_FLAGS := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
        -ffunction-sections -fdata-sections
RISCV_CC := riscv64-unknown-elf-gcc
RISCV_CORE_FLAGS := -march=rv32imafc -mabi=ilp32f -mcmodel=medany
$(eval $(call flags_record,check-arm,$(ARM_CC) $(ARM_CORE_FLAGS) $(CORE_CFLAGS)))
$(eval $(call flags_record,check-riscv,$(RISCV_CC) $(RISCV_CORE_FLAGS) $(CORE_CFLAGS)))
$(BUILD)/check-arm/%.o: core/%.c $(CORE_HDR) $(FLAGS_DIR)/check-arm
	@mkdir -p $(dir $@)
	$(Q)$(ARM_CC) $(ARM_CORE_FLAGS) $(CORE_CFLAGS) -Werror -c $< -o $@
$(BUILD)/check-riscv/%.o: core/%.c $(CORE_HDR) $(FLAGS_DIR)/check-riscv
	@mkdir -p $(dir $@)
	$(Q)$(RISCV_CC) $(RISCV_CORE_FLAGS) $(CORE_CFLAGS) -Werror -c $< -o $@

check-core: $(CORE_OBJ) $(patsubst core/%.c,$(BUILD)/check-arm/%.o,$(CORE_SRC)) \
            $(patsubst core/%.c,$(BUILD)/check-riscv/%.o,$(CORE_SRC))
	$(Q)tools/check_core_symbols.sh nm objdump $(CORE_OBJ)
	$(Q)tools/check_core_symbols.sh arm-none-eabi-nm arm-none-eabi-objdump \
		$(patsubst core/%.c,$(BUILD)/check-arm/%.o,$(CORE_SRC))
	$(Q)tools/check_core_symbols.sh riscv64-unknown-elf-nm riscv64-unknown-elf-objdump \
		$(patsubst core/%.c,$(BUILD)/check-riscv/%.o,$(CORE_SRC))
	@echo "core code size (Cortex-M4F, -O2):"; arm-none-eabi-size -t \
		$(patsubst core/%.c,$(BUILD)/check-arm/%.o,$(CORE_SRC)) | tail -1

# ------------------------------------------------------------- host code
$(eval $(call flags_record,host-obj,$(CC) $(HOST_CFLAGS) $(PKG_CFLAGS)))
$(HOST)/obj/%.o: %.c $(FLAGS_DIR)/host-obj
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) $(PKG_CFLAGS) -c $< -o $@

# ------------------------------------------------------- host-sim (celsim)
# celsim = host-sim/ (CLI, scene JSON loader, PNG writer, frame driver) plus
# the hal/sim backend (in-memory display, host clock) and the host side of the
# cel stream reader (tools/cels_read.c, over the core's decoder) and the
# typed-number reader all host programs share (tools/cli_num.c) over libcelscan.
CELSIM_SRC := $(sort $(wildcard host-sim/*.c)) $(sort $(wildcard hal/sim/*.c hal/host/*.c)) tools/cels_read.c \
        tools/cli.c tools/cli_num.c
CELSIM_OBJ := $(patsubst %.c,$(HOST)/obj/%.o,$(CELSIM_SRC))

$(HOST)/celsim: $(CELSIM_OBJ) $(HOST)/libcelscan_host.a
	$(Q)$(CC) -o $@ $(CELSIM_OBJ) $(HOST)/libcelscan_host.a $(PKG_LIBS) -lm -pthread

HOST_PROGRAMS += $(HOST)/celsim

# `make demo`: the demo panel at 720p, and 13 animation frames at the canvas
# size for t = 0, 1/6, ..., 2 s (frame-NNN.png is at t = NNN/6 s).
DEMO := $(BUILD)/demo
DEMO_FRAMES := $(foreach n,000 001 002 003 004 005 006 007 008 009 010 011 012,$(DEMO)/frame-$(n).png)
DEMO_TARGETS += $(DEMO)/demo.png $(DEMO_FRAMES)

$(DEMO)/demo.png: scenes/demo.json $(HOST)/celsim
	@mkdir -p $(dir $@)
	@echo "celsim render $< -o $@ --size 1280x720"
	$(Q)$(HOST)/celsim render $< -o $@ --size 1280x720

$(DEMO)/frame-%.png: scenes/demo.json $(HOST)/celsim
	@mkdir -p $(dir $@)
	$(Q)t=$$(awk -v n="$*" 'BEGIN { printf "%.6f", n / 6 }') && \
	echo "celsim render $< -o $@ --time $$t" && \
	$(HOST)/celsim render $< -o $@ --time $$t

# ----------------------------------------------------------------- tests
# Unit and image tests of the public API (core/celscan.h) against the
# independent long double reference in tests/ref/, on the harness in
# tests/testlib.h. tests/run.sh sums the results into a last line
# "N passed, M failed".
#   make test-unit   build the tests against build/host/libcelscan.a and run them
#   make test-asan   rebuild the core (hosted, not freestanding) and the tests with
#                    AddressSanitizer + UBSan (+ float-cast-overflow) into build/asan/
#                    and run them
# Tests of the parts in mk/*.mk are built by their fragments, not here.
FRAGMENT_TESTS := tests/test_cache.c tests/test_csg.c \
        tests/test_mcu_display.c tests/test_stream.c tests/test_exact.c \
        tests/test_beta.c tests/test_paint_json.c tests/test_scenes.c tests/test_bands.c \
        tests/test_rx_ring.c tests/test_display_conformance.c tests/test_panel_ssd1963.c \
        $(wildcard tests/test_svg*.c)
TEST_SRC := $(filter-out $(FRAGMENT_TESTS),$(sort $(wildcard tests/test_*.c)))
TEST_REF_SRC := $(sort $(wildcard tests/ref/*.c))
TEST_CFLAGS := -std=c11 $(OPT) -g $(FP_FLAGS) -Wall -Wextra -Wshadow -Icore -Itests -MMD -MP
# float-cast-overflow is not part of GCC's "undefined" group; a float to integer conversion out of
# range (NaN included) is undefined behaviour that the MCU and the host may resolve differently.
SAN_FLAGS := -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all \
        -fno-omit-frame-pointer
# One sanitizer build of the core (build/asan/libcelscan.a), compiled as the
# library is, with the sanitizers added, and linked by every ASan test program:
# the unit tests, exact, stream, scenes, wall and beta tests (each had compiled
# the core on its own, four times in all, and the beta tests once per program).
ASAN_CORE_CFLAGS := $(CORE_CFLAGS) $(SAN_FLAGS)
ASAN_TEST_CFLAGS := -std=c11 -O1 -g $(FP_FLAGS) -Wall -Wextra -Wshadow $(SAN_FLAGS) -Icore -Itests \
        -MMD -MP
ASAN_ENV := ASAN_OPTIONS=abort_on_error=0:detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1

HOST_TESTS := $(patsubst tests/%.c,$(HOST)/tests/%,$(TEST_SRC))
ASAN_TESTS := $(patsubst tests/%.c,$(ASAN)/tests/%,$(TEST_SRC))
HOST_TEST_REF_OBJ := $(patsubst tests/%.c,$(HOST)/tests/%.o,$(TEST_REF_SRC))
ASAN_TEST_REF_OBJ := $(patsubst tests/%.c,$(ASAN)/tests/%.o,$(TEST_REF_SRC))
ASAN_CORE_OBJ := $(patsubst core/%.c,$(ASAN)/core/%.o,$(CORE_SRC))

# tests/README.md lists every test file, and its example program passes (tests/readme_check.sh).
.PHONY: test-unit test-asan test-readme
test-readme: $(HOST)/libcelscan.a
	$(Q)sh tests/readme_check.sh $(HOST)/libcelscan.a
TEST_CMDS += "sh tests/readme_check.sh $(HOST)/libcelscan.a"

.SECONDARY: $(patsubst %,%.o,$(HOST_TESTS) $(ASAN_TESTS)) $(HOST_TEST_REF_OBJ) $(ASAN_TEST_REF_OBJ)
test-unit: $(HOST_TESTS)
	$(Q)sh tests/run.sh $(HOST_TESTS)

test-asan: $(ASAN_TESTS)
	$(Q)$(ASAN_ENV) sh tests/run.sh $(ASAN_TESTS)

$(eval $(call flags_record,host-test,$(CC) $(TEST_CFLAGS)))
$(eval $(call flags_record,asan-core,$(CC) $(ASAN_CORE_CFLAGS)))
$(eval $(call flags_record,asan-test,$(CC) $(ASAN_TEST_CFLAGS)))
$(HOST)/tests/%.o: tests/%.c Makefile $(FLAGS_DIR)/host-test
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(TEST_CFLAGS) -c $< -o $@

$(HOST)/tests/test_%: $(HOST)/tests/test_%.o $(HOST_TEST_REF_OBJ) $(HOST)/libcelscan.a
	$(Q)$(CC) $(TEST_CFLAGS) $^ -lm -o $@

$(ASAN)/core/%.o: core/%.c $(CORE_HDR) Makefile $(FLAGS_DIR)/asan-core
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(ASAN_CORE_CFLAGS) -c $< -o $@

$(ASAN)/libcelscan.a: $(ASAN_CORE_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

$(ASAN)/tests/%.o: tests/%.c Makefile $(FLAGS_DIR)/asan-test
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(ASAN_TEST_CFLAGS) -c $< -o $@

$(ASAN)/tests/test_%: $(ASAN)/tests/test_%.o $(ASAN_TEST_REF_OBJ) $(ASAN)/libcelscan.a
	$(Q)$(CC) $(ASAN_TEST_CFLAGS) $^ -lm -o $@

# ------------------------------------------------------------ fragments
# Larger parts of the project keep their rules in mk/*.mk, still one make
# invocation. A fragment appends its test targets to TEST_TARGETS, its
# programs to HOST_PROGRAMS and its demo steps to DEMO_TARGETS.
include $(sort $(wildcard mk/*.mk))

# Everything `make test` runs, summed by tests/run.sh into one last line
# "N passed, M failed". Fragments add test programs (each printing
# "<name>: N passed, M failed") to TEST_PROGS with their build prerequisites
# in TEST_DEPS, shell commands to TEST_CMDS, and make targets that run tests
# (and print such a line) to TEST_TARGETS.
all: $(HOST_PROGRAMS)
demo-all: $(DEMO_TARGETS)
	@echo "demo: $(DEMO_TARGETS)" | fmt -w 100

test-all: check-core $(HOST_PROGRAMS) $(HOST_TESTS) $(ASAN_TESTS) $(TEST_DEPS)
	$(Q)$(ASAN_ENV) tests/run.sh $(HOST_TESTS) $(ASAN_TESTS) $(TEST_PROGS) -- $(TEST_CMDS) \
		$(foreach t,$(TEST_TARGETS),"$(MAKE) --no-print-directory $(t)")

# build/pkg/ holds package roots and consumer builds (mk/install.mk): their
# *.d are directories (sysusers.d) and other builds' dependency files.
-include $(shell find $(BUILD) -path $(BUILD)/pkg -prune -o -name '*.d' -type f -print 2>/dev/null)

clean:
	rm -rf $(BUILD)
