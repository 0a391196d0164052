# Cross-compiling the portable core for a Cortex-M0+ (no FPU), as a firmware
# port would:  cmake -S . -B build-arm -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
# No OS, no startup files: test the compiler by building a library only.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(XGO_MCU_FLAGS "-mcpu=cortex-m0plus -mthumb" CACHE STRING "CPU flags for the core")
set(CMAKE_C_FLAGS_INIT "${XGO_MCU_FLAGS} -ffreestanding -ffunction-sections -fdata-sections")
set(CMAKE_C_FLAGS_MINSIZEREL_INIT "-Os")
set(XGO_BUILD_HOST OFF CACHE BOOL "" FORCE)
set(XGO_BUILD_TESTS OFF CACHE BOOL "" FORCE)
set(XGO_BUILD_TOOLS OFF CACHE BOOL "" FORCE)
