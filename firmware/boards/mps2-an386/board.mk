# board.mk - mps2-an386: Arm MPS2 + AN386 (Cortex-M4F), runs under QEMU.
#
# Sets the BOARD_* variables that mk/firmware.mk reads for this board.
BOARD_CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
BOARD_LDSCRIPT := linker/mps2-an386.ld
BOARD_STACK := 2048
BOARD_SRC := firmware/boards/mps2-an386/board.c \
             firmware/boards/cortex-m/cm_startup.c \
             hal/mcu/semihost.c hal/mcu/panel_semihost.c hal/mcu/rx_ring.c
BOARD_QEMU := qemu-system-arm -M mps2-an386
