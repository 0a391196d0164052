#!/usr/bin/env bash
# tools/mcu/run.sh - the portable core RUNNING on a Cortex-M0 (docs/mcu.md).
#
# Builds tools/mcu/mcu_selftest.c with the core twice: bare metal for a
# Cortex-M0+ (arm-none-eabi-gcc, own startup and linker script, no C library)
# and natively for the host (gcc). Runs the first in QEMU's micro:bit (nRF51,
# Cortex-M0; ARMv6-M like the M0+) with exact instruction counting, the second
# directly, and requires their RESULT lines to be identical. Prints the
# instruction counts and the image sizes. Exits non-zero on any failure.
#
# Needs: arm-none-eabi-gcc (+ libnewlib-arm-none-eabi for the string.h header
# the core includes; nothing of newlib is linked), qemu-system-arm, gcc.
# Environment: XGO_MCU_BUILD (default build-mcu, build-mcu-m3), XGO_MCU_OPT (default -Os),
# XGO_MCU_TARGET: m0 (default: built for a Cortex-M0+, run on the micro:bit's
# M0) or m3 (for comparison: built for and run on a Cortex-M3, mps2-an385).
# XGO_MCU_CONFIG: full (default: the core with every feature and the host's
# buffers) or firmware (the options and buffer sizes the firmware images
# ship with, XGO_FIRMWARE_OPTIONS and XGO_FIRMWARE_BUFFERS in CMakeLists.txt:
# what an MCU actually runs). Host and MCU are built alike either way, so the
# RESULT lines compare one configuration on both architectures. (The two
# configurations' wire digests differ: with the firmware's 113-byte transmit
# buffer the self test reads the register file in two requests, and the
# diagnostic block counts the extra frame.)
set -euo pipefail
cd "$(dirname "$0")/../.."

target=${XGO_MCU_TARGET:-m0}
config=${XGO_MCU_CONFIG:-full}
case "$config" in
  full) suffix=; cfgdefs=() ;;
  firmware) # the lists' defaults, read where CMake keeps them (one source of truth)
    suffix=-fw
    mapfile -t cfgdefs < <(sed -n 's/^xgo_firmware_list(XGO_FIRMWARE_\(OPTIONS\|BUFFERS\) "\([^"]*\)".*/\2/p' \
      CMakeLists.txt | tr ';' '\n' | sed '/^$/d; s/^/-D/')
    [ "${#cfgdefs[@]}" -gt 0 ] || { echo "no XGO_FIRMWARE_OPTIONS in CMakeLists.txt" >&2; exit 2; } ;;
  *) echo "XGO_MCU_CONFIG must be full or firmware" >&2; exit 2 ;;
esac
if [ "$target" = m0 ]; then out=${XGO_MCU_BUILD:-build-mcu$suffix}; else out=${XGO_MCU_BUILD:-build-mcu-$target$suffix}; fi
opt=${XGO_MCU_OPT:--Os}
mcu=tools/mcu
mkdir -p "$out/obj"

warn=(-std=c99 -Wall -Wextra -Werror -pedantic)
case "$target" in
  m0) cpu=(-mcpu=cortex-m0plus -mthumb); defs=(); machine=microbit; shift=8 ;;
  m3) cpu=(-mcpu=cortex-m3 -mthumb); defs=(-DMCU_MPS2_AN385); machine=mps2-an385; shift=7 ;;
  *) echo "XGO_MCU_TARGET must be m0 or m3" >&2; exit 2 ;;
esac
# The measured image is built as a firmware would ship: the core's checks
# compiled out (MinSizeRel has NDEBUG); a second image turns them on to show
# the hook working.
armflags=("${cpu[@]}" "$opt" "${defs[@]}" "${cfgdefs[@]}" -g -ffreestanding -ffunction-sections -fdata-sections
  -Iinclude -Isrc/core -Itest/support -I"$mcu")
nochecks=(-DXGO_ASSERT_ENABLED=0)

echo "== build: bare-metal image (arm-none-eabi-gcc ${cpu[*]} $opt -ffreestanding -nostdlib), $config configuration ${cfgdefs[*]}"
objs=()
# The board without the device layer (src/core/device.c needs a port's
# xgo_port_* functions; this self test drives the board directly).
core_srcs=()
for src in src/core/*.c; do
  [ "$src" = src/core/device.c ] || core_srcs+=("$src")
done
mkdir -p "$out/obj-checks"
checked=()
for src in "${core_srcs[@]}"; do
  obj="$out/obj/core_$(basename "${src%.c}").o"
  arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" "${nochecks[@]}" -c "$src" -o "$obj"
  objs+=("$obj")
  obj="$out/obj-checks/core_$(basename "${src%.c}").o"
  arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" -DXGO_ASSERT_ENABLED=1 -c "$src" -o "$obj"
  checked+=("$obj")
done
for name in measure semihost startup; do
  arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" -c "$mcu/$name.c" -o "$out/obj/$name.o"
  objs+=("$out/obj/$name.o")
done
arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" -c test/support/board_io.c -o "$out/obj/board_io.o"
objs+=("$out/obj/board_io.o")
# Our memcpy/memset must not be turned back into calls to themselves.
arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" -fno-tree-loop-distribute-patterns \
  -c ports/cortex-m/libc_min.c -o "$out/obj/libc_min.o"
arm-none-eabi-gcc "${cpu[@]}" -c "$mcu/measure.S" -o "$out/obj/measure_s.o"
objs+=("$out/obj/libc_min.o" "$out/obj/measure_s.o")
link() { # link ELF MAIN_OBJECT [CORE_OBJECTS...]: default, the measured core
  local elf=$1 main=$2
  shift 2
  if [ $# -eq 0 ]; then set -- "${objs[@]}"; else set -- "$@" "${objs[@]:${#core_srcs[@]}}"; fi
  arm-none-eabi-gcc "${cpu[@]}" -nostdlib -nostartfiles -T "$mcu/link.ld" -Wl,--gc-sections \
    -Wl,-Map="${elf%.elf}.map" "$main" "$@" -lgcc -o "$elf"
}
arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" "${nochecks[@]}" -c "$mcu/mcu_selftest.c" \
  -o "$out/obj/mcu_selftest.o"
elf="$out/mcu_selftest.elf"
link "$elf" "$out/obj/mcu_selftest.o"
# The same program faulting on purpose: checks the fault handlers' exit.
arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" "${nochecks[@]}" -DMCU_SELFTEST_FAULT \
  -c "$mcu/mcu_selftest.c" -o "$out/obj/mcu_selftest_fault.o"
link "$out/mcu_fault.elf" "$out/obj/mcu_selftest_fault.o"
# The core with its checks on, and a caller's bug on purpose: the hook reports.
arm-none-eabi-gcc "${warn[@]}" "${armflags[@]}" -DXGO_ASSERT_ENABLED=1 -DMCU_SELFTEST_ASSERT \
  -c "$mcu/mcu_selftest.c" -o "$out/obj-checks/mcu_selftest_assert.o"
link "$out/mcu_assert.elf" "$out/obj-checks/mcu_selftest_assert.o" "${checked[@]}"

echo "== build: host variant (gcc -O2)"
host="$out/mcu_selftest_host"
gcc "${warn[@]}" -O2 "${nochecks[@]}" "${cfgdefs[@]}" -Iinclude -Isrc/core -Itest/support -I"$mcu" "$mcu/mcu_selftest.c" "$mcu/host_port.c" \
  test/support/board_io.c "${core_srcs[@]}" -o "$host"

echo "== sizes"
arm-none-eabi-size "$elf"
# Flash/RAM by origin, from the link map.
awk -v core='obj/core_' -v other=harness -f "$mcu/map_sizes.awk" "$out/mcu_selftest.map"

echo "== run: host"
"$host" >"$out/host.out"
grep '^RESULT' "$out/host.out" >"$out/host.result"

qemu() { # qemu ELF: runs it with exact instruction counting (measure.h)
  timeout 120 qemu-system-arm -M "$machine" -display none -monitor none -serial none \
    -icount shift="$shift" -semihosting-config enable=on,target=native -kernel "$1"
}

echo "== run: QEMU -M $machine, -icount shift=$shift"
set +e
qemu "$elf" >"$out/mcu.out" 2>&1
rc=$?
set -e
cat "$out/mcu.out"
if [ "$rc" -ne 0 ]; then
  echo "FAIL: the bare-metal self test exited with $rc (124 = timeout; startup.c: 90..93 = faults)"
  exit 1
fi
grep '^RESULT' "$out/mcu.out" >"$out/mcu.result"

echo "== run: a HardFault on purpose (expects exit 91 and the report)"
set +e
qemu "$out/mcu_fault.elf" >"$out/mcu_fault.out" 2>&1
rc=$?
set -e
cat "$out/mcu_fault.out"; echo
if [ "$rc" -ne 91 ] || ! grep -q 'FAULT HardFault pc=' "$out/mcu_fault.out"; then
  echo "FAIL: the fault handler did not report and exit with 91 (got $rc)"
  exit 1
fi

echo "== run: a caller's bug on purpose, the core's checks on (expects exit 19 and the check)"
set +e
qemu "$out/mcu_assert.elf" >"$out/mcu_assert.out" 2>&1
rc=$?
set -e
cat "$out/mcu_assert.out"
if [ "$rc" -ne 19 ] || ! grep -q '^ASSERT .*board\.c:[0-9]*: joint < XGO_SERVO_COUNT' "$out/mcu_assert.out"; then
  echo "FAIL: the core's check did not reach the port's hook (got $rc)"
  exit 1
fi

echo "== compare: host vs $machine RESULT lines"
if ! diff -u "$out/host.result" "$out/mcu.result"; then
  echo "FAIL: the host and the MCU computed different results"
  exit 1
fi
echo "identical: $(wc -l <"$out/mcu.result") RESULT lines (host gcc -O2, ${cpu[0]#-mcpu=} $opt on $machine, $config configuration)"
