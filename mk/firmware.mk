# mk/firmware.mk - bare-metal firmware images, QEMU tests and instruction counts.
#
#   make firmware [BOARD=mps2-an386]   build/<board>/celfw.elf (+ .map, .bin), memory
#                                      use printed and the budgets enforced
#   make firmware-all                  every board in firmware/boards/*/board.mk
#   make qemu-test [BOARD=B]           boot the mps2-an386 and netduinoplus2 images (or
#                                      B's) in QEMU, render the built-in scenes and
#                                      streamed ones (sent over the UART at full speed
#                                      while frames render), compare with celsim and the
#                                      host (CRC, floats, pixels); damaged streams; an
#                                      injected UART overrun; faults
#   make test-mcu-display              unit test of hal/mcu/mcu_display.c on the host
#   make test-rx-ring                  unit test of hal/mcu/rx_ring.c (UART receive ring)
#   make qemu-run STREAM=F SIZE=480x272 TIME=0.5 [AA=16] [BOARD=netduinoplus2]
#                                      boot, stream F (.cels, or .json compiled first)
#                                      over the UART, print the frame's `frame crc32`
#                                      line, as `celsim render F --size --time --crc`
#   make qemu-run SCENE=signage SIZE=480x272 TIME=0.75 [AA=16]
#                                      the same for a built-in scene
#   make qemu-insn                     executed instructions per frame and per line
#                                      (QEMU TCG plugin, tools/qemu-insn)
#
# Each board folder has a board.mk that sets BOARD_CPU, BOARD_LDSCRIPT,
# BOARD_STACK, BOARD_SRC and optionally BOARD_QEMU; the rules below are
# generated once per board, so all boards build in one make invocation.
# The core is compiled again per board with the board's capacities
# (firmware/boards/<board>/cs_board_config.h, named by CS_CFG_FILE).

BOARD ?= mps2-an386
FW_BOARDS := $(patsubst firmware/boards/%/board.mk,%,$(wildcard firmware/boards/*/board.mk))
FW_QEMU_BOARD := mps2-an386

FW_COMMON_SRC := firmware/main_mcu.c firmware/fw_render.c firmware/fw_stream.c firmware/fw_print.c \
                 firmware/fw_args.c firmware/fw_mem.c firmware/fw_clock.c \
                 firmware/scenes/fw_scenes.c hal/mcu/mcu_display.c
# No C library and no heap: -nostdlib, -ffreestanding; GCC may not invent
# memcpy/memset calls (-fno-tree-loop-distribute-patterns); sqrtf is one
# VSQRT (-fno-math-errno, in FP_FLAGS with -ffp-contract=off); libgcc gives
# the 64-bit division helpers.
# Flash is the scarce resource on a board (see the budgets fw_budget.sh
# enforces), and most of the code runs once per stream or per frame, not
# per line: that cold code is optimised for size (FW_COLD_SRC, -Os) and the
# per-line path for speed ($(OPT)). The optimisation level changes no
# result: -ffp-contract=off and no fast-math keep every float operation as
# written, so the frames' CRCs are the same either way (qemu-test checks).
# Frame preparation (cs_frame.c, cs_paint.c's compile) runs once per band,
# the messages once per error: -Os there costs 3 % of a frame's
# instructions and saves 2.4 KB. The exception is cs_nurbs.c, the knot
# spans to polynomial segments that every band redoes for each contour
# meeting its rows: with the line code's options it gives 176 k fewer
# instructions per board demo frame for 316 B (cs_frame.c or cs_paint.c
# there cost 1.0 and 0.65 KB for nothing). The line code (FW_LINE_SRC: spans
# and compositing) keeps -O2 but inlines only small functions (FW_LINE_OPT):
# 4 KB less for several per cent more instructions per frame
# (firmware/README.md), where all of it at -Os would cost 17 % more. The
# limit is 30 (it was 20): 112 k fewer instructions per board demo frame
# for 116 B; 40 and 50 gave less per byte.
# The image is linked with -flto: GCC keeps each file's -Os or -O2 per
# function, and inlines across the core's stage files (cs__line_active,
# cs__crossings_at, cs__region_coverage are called per line from other
# files) and drops what a board never reaches (the pixel formats other than
# the panel's): 4.5 KB less flash and 3.6 % fewer instructions per board
# demo line (firmware/README.md). fw_mem.c stays outside LTO: the memcpy and
# memset that code generation itself calls must exist as ordinary symbols
# when the LTO objects are compiled (-u keeps those two through --gc-sections).
FW_OPT = $(OPT)
FW_COLD_OPT := -Os
FW_LINE_OPT = $(OPT) -finline-limit=30
# Three line files inline more (FW_HOT_OPT): the root solver's Horner steps
# (cs_poly.c) and the RGB565 run conversion (cs_pixfmt.c) gave 285 k fewer
# instructions per board demo frame for 396 B, paid for by the CRC-32's
# nibble table on the boards whose panel reads back (CS_CFG_CRC32_TABLE);
# the compositing (cs_composite.c) 65 k for 772 B, paid for by the compact
# sRGB table on those boards (CS_CFG_SRGB_COMPACT). cs_cross.c at 80 now
# gives nothing (cs__horner and cs__horner_d are forced inline, cs_internal.h
# CS__LINE_INLINE) for 360 B (firmware/README.md).
FW_HOT_OPT = $(OPT) -finline-limit=80
FW_HOT_SRC := core/cs_poly.c core/cs_pixfmt.c core/cs_composite.c
FW_LINE_SRC := core/cs_cross.c core/cs_coverage.c core/cs_composite.c core/cs_line.c \
               core/cs_crc32.c core/cs_nurbs.c
FW_COLD_SRC := core/cs_stream.c core/cs_stream_apply.c core/cs_scene.c core/cs_edit.c \
               core/cs_anim.c core/cs_frame.c core/cs_paint.c core/cs_status.c \
               core/cs_damage.c firmware/fw_render.c \
               firmware/main_mcu.c firmware/fw_stream.c firmware/fw_print.c firmware/fw_args.c \
               firmware/fw_mem.c firmware/fw_clock.c firmware/scenes/fw_scenes.c \
               $(wildcard firmware/boards/*/board.c firmware/boards/stm32f4/*.c) \
               firmware/boards/cortex-m/cm_startup.c hal/mcu/rx_ring.c hal/mcu/semihost.c \
               hal/mcu/panel_semihost.c
FW_CFLAGS := -std=c11 -g $(FP_FLAGS) $(WARN) -ffreestanding -fno-builtin \
        -fno-tree-loop-distribute-patterns -fno-stack-protector -fno-common \
        -ffunction-sections -fdata-sections -MMD -MP -flto
FW_LDFLAGS := -nostdlib -flto -Wl,-u,memcpy,-u,memset -Wl,--gc-sections \
        -Llinker -Wl,--no-warn-rwx-segments

define FW_BOARD_RULES
BOARD_CPU :=
BOARD_LDSCRIPT :=
BOARD_STACK := 2048
BOARD_SRC :=
BOARD_QEMU :=
include firmware/boards/$(1)/board.mk
FW_CPU_$(1) := $$(BOARD_CPU)
FW_LD_$(1) := $$(BOARD_LDSCRIPT)
FW_STACK_$(1) := $$(BOARD_STACK)
FW_QEMU_$(1) := $$(BOARD_QEMU)
FW_INC_$(1) := -Icore -Ifirmware -Ifirmware/scenes -Ifirmware/boards -Ifirmware/boards/cortex-m \
        -Ifirmware/boards/$(1) -Ifirmware/boards/stm32f4 -Ihal/mcu -Ihal -DHAL_ERR_LEN=4 \
        -DCS_CFG_FILE='"cs_board_config.h"'
FW_OBJ_$(1) := $$(patsubst %.c,$(BUILD)/$(1)/obj/%.o,$(CORE_SRC) $(FW_COMMON_SRC) $$(BOARD_SRC))

$$(eval $$(call flags_record,fw-$(1),$(ARM_CC) $$(FW_CPU_$(1)) $(OPT) $(FW_COLD_OPT) $(FW_CFLAGS) \
        $$(FW_INC_$(1)) cold: $(FW_COLD_SRC) line: $(FW_LINE_OPT) $(FW_LINE_SRC) \
        hot: $(FW_HOT_OPT) $(FW_HOT_SRC)))
$(BUILD)/$(1)/obj/%.o: %.c $(FLAGS_DIR)/fw-$(1)
	@mkdir -p $$(dir $$@)
	$(Q)$(ARM_CC) $$(FW_CPU_$(1)) $$(FW_OPT) $(FW_CFLAGS) $$(FW_INC_$(1)) -c $$< -o $$@
$$(patsubst %.c,$(BUILD)/$(1)/obj/%.o,$(FW_COLD_SRC)): FW_OPT := $(FW_COLD_OPT)
$$(patsubst %.c,$(BUILD)/$(1)/obj/%.o,$(FW_LINE_SRC)): FW_OPT := $(FW_LINE_OPT)
$$(patsubst %.c,$(BUILD)/$(1)/obj/%.o,$(FW_HOT_SRC)): FW_OPT := $(FW_HOT_OPT)
$(BUILD)/$(1)/obj/firmware/fw_mem.o: FW_OPT := $(FW_COLD_OPT) -fno-lto

$(BUILD)/$(1)/celfw.elf: $$(FW_OBJ_$(1)) $$(FW_LD_$(1)) linker/sections.ld
	$(Q)$(ARM_CC) $$(FW_CPU_$(1)) $(FW_COLD_OPT) $(FW_CFLAGS) $(FW_LDFLAGS) -T$$(FW_LD_$(1)) \
		-Wl,--defsym=__stack_size=$$(FW_STACK_$(1)) -Wl,-Map=$(BUILD)/$(1)/celfw.map \
		$$(FW_OBJ_$(1)) -lgcc -o $$@
	$(Q)arm-none-eabi-objcopy -O binary $$@ $(BUILD)/$(1)/celfw.bin

.PHONY: firmware-$(1) qemu-test-$(1)
firmware-$(1): $(BUILD)/$(1)/celfw.elf
	$(Q)tools/fw_budget.sh $(1) $(BUILD)/$(1)/celfw.elf $(BUILD)/$(1)/celfw.map
qemu-test-$(1): firmware-$(1) $(HOST)/fw_host_ref $(HOST)/fw_cels_gen $(HOST)/celsim $(HOST)/celc
	$(Q)$$(if $$(FW_QEMU_$(1)),FW_QEMU="$$(FW_QEMU_$(1))" tools/fw_qemu_test.sh \
		$(BUILD)/$(1)/celfw.elf $(BUILD)/$(1)/qemu-test $(1),@echo "qemu-test $(1): no QEMU machine (BOARD_QEMU)"; false)
endef
$(foreach b,$(FW_BOARDS),$(eval $(call FW_BOARD_RULES,$(b))))

.PHONY: firmware firmware-all qemu-test qemu-run qemu-insn
firmware: firmware-$(BOARD)
firmware-all: $(addprefix firmware-,$(FW_BOARDS))

# ---------------------------------------------------------- host side
# The reference renderer for the built-in scenes, and the QEMU plugin.
# fw_host_ref renders built-in scenes, the animated C scene and decoded
# streams; the qemu test sends scene JSON compiled by celc, and fw_cels_gen
# writes the stream of the animated C scene.
$(HOST)/obj/tests/fw_host_ref.o $(HOST)/obj/tests/fw_cels_gen.o: HOST_CFLAGS += -Ifirmware/scenes -Itools
$(HOST)/obj/firmware/scenes/fw_scenes.o: HOST_CFLAGS += -Ifirmware/scenes
$(HOST)/fw_host_ref: $(HOST)/obj/tests/fw_host_ref.o $(HOST)/obj/firmware/scenes/fw_scenes.o \
                     $(HOST)/obj/tests/fw_tracks_scene.o $(HOST)/obj/tools/cels_read.o \
                     $(HOST)/libcelscan.a
	$(Q)$(CC) $^ -o $@
$(HOST)/fw_cels_gen: $(HOST)/obj/tests/fw_cels_gen.o $(HOST)/obj/tests/fw_tracks_scene.o \
                     $(HOST)/obj/tools/cels_write.o $(HOST)/libcelscan.a
	$(Q)$(CC) $^ -lm -o $@
HOST_PROGRAMS += $(HOST)/fw_host_ref $(HOST)/fw_cels_gen

# The MCU display backend is plain C: its unit test runs on the host.
$(HOST)/obj/tests/test_mcu_display.o $(HOST)/obj/hal/mcu/mcu_display.o: HOST_CFLAGS += -Ihal/mcu -Itests
$(HOST)/test_mcu_display: $(HOST)/obj/tests/test_mcu_display.o $(HOST)/obj/hal/mcu/mcu_display.o \
                          $(HOST)/libcelscan.a
	$(Q)$(CC) $^ -lz -o $@

.PHONY: test-mcu-display
test-mcu-display: $(HOST)/test_mcu_display
	$(Q)$<

# The UART receive ring is plain C too.
$(HOST)/obj/tests/test_rx_ring.o $(HOST)/obj/hal/mcu/rx_ring.o: HOST_CFLAGS += -Ihal/mcu -Itests
$(HOST)/test_rx_ring: $(HOST)/obj/tests/test_rx_ring.o $(HOST)/obj/hal/mcu/rx_ring.o
	$(Q)$(CC) $^ -o $@

.PHONY: test-rx-ring
test-rx-ring: $(HOST)/test_rx_ring
	$(Q)$<

# A TCG plugin is a shared object QEMU loads; it uses no glib and no QEMU
# header (Debian ships neither for plugins), see tools/qemu-insn.
$(HOST)/libinsncount.so: tools/qemu-insn/insncount.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) -std=c11 -O2 -Wall -Wextra -shared -fPIC -fvisibility=hidden $< -o $@

# ------------------------------------------------------------ running
# qemu-test runs every board that has a QEMU machine, or only BOARD when it
# is given (make qemu-test BOARD=netduinoplus2).
FW_QEMU_ELF := $(BUILD)/$(FW_QEMU_BOARD)/celfw.elf
FW_QEMU_BOARDS := $(foreach b,$(FW_BOARDS),$(if $(FW_QEMU_$(b)),$(b)))
qemu-test: $(addprefix qemu-test-,$(if $(filter command line environment,$(origin BOARD)),\
                                       $(BOARD),$(FW_QEMU_BOARDS)))

STREAM ?=
SCENE ?= signage
SIZE ?= 480x272
TIME ?= 0
AA ?= 16
FW_RUN_BOARD := $(if $(filter command line environment,$(origin BOARD)),$(BOARD),$(FW_QEMU_BOARD))
qemu-run: firmware-$(FW_RUN_BOARD) $(if $(STREAM),$(HOST)/celc)
	$(Q)FW_QEMU="$(FW_QEMU_$(FW_RUN_BOARD))" tools/fw_qemu_run.sh $(BUILD)/$(FW_RUN_BOARD)/celfw.elf \
		$(if $(STREAM),--stream "$(STREAM)",--scene "$(SCENE)") "$(SIZE)" "$(TIME)" "$(AA)"

# The full demo (rendered in bands), the reduced board demo, the animated
# scene and the beta stack, streamed, at 480x272 with 5 and 16
# sub-scanlines; then the built-in jobs; then 2 s of the board's animated
# scene (scenes/board-anim.json) at 60 frames a second with damage.
FW_INSN := $(BUILD)/$(FW_QEMU_BOARD)/insn
qemu-insn: firmware-$(FW_QEMU_BOARD) $(HOST)/libinsncount.so $(HOST)/fw_cels_gen $(HOST)/celc
	@mkdir -p $(FW_INSN)/streams
	$(Q)$(HOST)/celc compile scenes/demo.json -o $(FW_INSN)/streams/demo.cels
	$(Q)$(HOST)/celc compile scenes/demo-board.json -o $(FW_INSN)/streams/demo-board.cels
	$(Q)$(HOST)/fw_cels_gen --tracks $(FW_INSN)/streams/tracks.cels
	$(Q)$(HOST)/celc compile scenes/beta-stack.json -o $(FW_INSN)/streams/beta-stack.cels
	$(Q)tools/qemu-insn/measure.sh $(FW_QEMU_ELF) $(HOST)/libinsncount.so $(FW_INSN)/stream \
		"frames=480x272@0:5,480x272@0:16" $(FW_INSN)/streams/demo.cels \
		$(FW_INSN)/streams/demo-board.cels \
		$(FW_INSN)/streams/tracks.cels $(FW_INSN)/streams/beta-stack.cels
	$(Q)tools/qemu-insn/measure.sh $(FW_QEMU_ELF) $(HOST)/libinsncount.so $(FW_INSN)/builtin
	$(Q)$(HOST)/celc compile scenes/board-anim.json -o $(FW_INSN)/streams/board-anim.cels
	$(Q)tools/qemu-insn/measure.sh $(FW_QEMU_ELF) $(HOST)/libinsncount.so $(FW_INSN)/anim \
		"frames=480x272@0:5 repeat=120 step_ms=17 damage=1 render=end" \
		$(FW_INSN)/streams/board-anim.cels

# firmware-all: every board's image builds and fits its flash and RAM
# budgets (qemu-test boots the boards that QEMU models: mps2-an386 and
# netduinoplus2, which runs the stm32f407-ssd1963 board's STM32 drivers).
TEST_TARGETS += test-mcu-display test-rx-ring $(addprefix qemu-test-,$(FW_QEMU_BOARDS)) firmware-all

# celsim's damage report (--repeat N --time-step S), the host side of the
# boards' damage (tests/cli_damage.sh).
TEST_CMDS += "sh tests/cli_damage.sh $(HOST)"
