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
        -Icore -Ihal -Ihost-sim -D_POSIX_C_SOURCE=200809L -MMD -MP
CORE_CFLAGS := -std=c11 $(OPT) -g $(FP_FLAGS) $(WARN) $(CORE_FREESTANDING) -Icore -MMD -MP

.PHONY: all deps demo demo-all test test-all check-core clean
all: $(HOST)/celsim

# The entry points set up the machine first, then run in a fresh make so
# that pkg-config sees what was just installed.
deps:
	$(Q)tools/install-deps.sh

test:
	$(Q)tools/install-deps.sh
	$(Q)$(MAKE) --no-print-directory test-all

demo:
	$(Q)tools/install-deps.sh
	$(Q)$(MAKE) --no-print-directory demo-all

# ------------------------------------------------------------------ core
$(HOST)/core/%.o: core/%.c $(CORE_HDR)
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
$(BUILD)/check-arm/%.o: core/%.c $(CORE_HDR)
	@mkdir -p $(dir $@)
	$(Q)$(ARM_CC) $(ARM_CORE_FLAGS) $(CORE_CFLAGS) -Werror -c $< -o $@
$(BUILD)/check-riscv/%.o: core/%.c $(CORE_HDR)
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
$(HOST)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) $(PKG_CFLAGS) -c $< -o $@

# ------------------------------------------------------- host-sim (celsim)
# (section owned by the host-sim work)

# ----------------------------------------------------------------- tests
# (section owned by the tests work)

# ------------------------------------------------------------ fragments
# Larger parts of the project keep their rules in mk/*.mk, still one make
# invocation. A fragment appends its test targets to TEST_TARGETS, its
# programs to HOST_PROGRAMS and its demo steps to DEMO_TARGETS.
include $(sort $(wildcard mk/*.mk))

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)

clean:
	rm -rf $(BUILD)
