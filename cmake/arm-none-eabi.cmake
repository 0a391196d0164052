# Cross-compiling the portable core for a Cortex-M0+ (no FPU), as a firmware
# port would:  cmake -S . -B build-arm -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake
# With -DXGO_PORT=stm32f1|nrf51 the firmware image for that port too (ports/).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
# No OS, no startup files: test the compiler by building a library only.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
# Code generation the STM32 (Cortex-M3) image does without, for flash:
# the second scheduling pass (it reorders for pipeline stalls only), value
# range propagation and the loop counter canonicalisation, about 350 bytes
# together; the tick is no longer in instructions (run.sh's M3 firmware
# configuration built with them: 6,543.7 -> 6,514.0). On the Cortex-M0
# they save less and cost instructions (-fno-tree-loop-ivcanon: +36 a
# tick), so the nRF51 image keeps plain -Os.
set(xgo_size_flags "")
# The CPU: a firmware port's own (-DXGO_PORT=...), else a Cortex-M0+.
if(XGO_PORT STREQUAL "stm32f1")
  set(xgo_default_cpu "-mcpu=cortex-m3 -mthumb")
  set(xgo_size_flags "-fno-schedule-insns2 -fno-tree-vrp -fno-tree-loop-ivcanon")
elseif(XGO_PORT STREQUAL "nrf51")
  set(xgo_default_cpu "-mcpu=cortex-m0 -mthumb")
else()
  set(xgo_default_cpu "-mcpu=cortex-m0plus -mthumb")
endif()
set(XGO_MCU_FLAGS "${xgo_default_cpu}" CACHE STRING "CPU flags for the core")
set(CMAKE_C_FLAGS_INIT "${XGO_MCU_FLAGS} ${xgo_size_flags} -ffreestanding -ffunction-sections -fdata-sections")
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-Os")
set(XGO_BUILD_HOST OFF CACHE BOOL "" FORCE)
set(XGO_BUILD_TESTS OFF CACHE BOOL "" FORCE)
set(XGO_BUILD_TOOLS OFF CACHE BOOL "" FORCE)
