# arm-none-eabi.cmake - CMake toolchain file for Cortex-M4F with hard float, as
# libcelscan's cortex-m4f variant is built (celscanConfig.cmake picks it from
# CMAKE_SYSTEM_PROCESSOR).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_C_FLAGS_INIT "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
# the compiler check links no program: there is no board support to link it with
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
