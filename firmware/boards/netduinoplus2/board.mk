# board.mk - netduinoplus2: QEMU's STM32F405 machine, running the STM32
# drivers of stm32f407-ssd1963 with the semihosting panel of mps2-an386.
# USART2 (the stream link) is QEMU's second -serial.
BOARD_CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
BOARD_LDSCRIPT := linker/stm32f407xg.ld
BOARD_STACK := 2048
BOARD_SRC := firmware/boards/netduinoplus2/board.c \
             firmware/boards/stm32f4/stm32_clock.c firmware/boards/stm32f4/stm32_usart.c \
             firmware/boards/cortex-m/cm_startup.c hal/mcu/semihost.c hal/mcu/panel_semihost.c \
             hal/mcu/rx_ring.c
BOARD_QEMU := qemu-system-arm -M netduinoplus2 -serial null
