# board.mk - stm32f407-ssd1963: STM32F407 + SSD1963 480x272 TFT on FSMC.
# Built and size-checked; QEMU has no FSMC, so this image is not run, but its
# STM32 drivers (firmware/boards/stm32f4) run in CI as board netduinoplus2.
BOARD_CPU := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
BOARD_LDSCRIPT := linker/stm32f407xg.ld
BOARD_STACK := 2048
BOARD_SRC := firmware/boards/stm32f407-ssd1963/board.c \
             firmware/boards/stm32f4/stm32_clock.c firmware/boards/stm32f4/stm32_usart.c \
             firmware/boards/cortex-m/cm_startup.c hal/mcu/panel_ssd1963.c hal/mcu/rx_ring.c
