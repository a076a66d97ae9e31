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
# Round-robin TCG: with the default multi-threaded TCG the vCPU thread, which
# polls the USART's registers while the link is idle, takes QEMU's big lock so
# often that the main loop delivering link bytes starved for 5 s in 4 of 100
# streamed runs on a loaded machine (a stream cut short); 0 of 100 this way.
BOARD_QEMU := qemu-system-arm -M netduinoplus2 -accel tcg,thread=single -serial null
