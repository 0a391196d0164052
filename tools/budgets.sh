#!/usr/bin/env bash
# tools/budgets.sh [HOST_BUILD] - every budget of docs/mcu.md ("Budgets"),
# measured and printed next to its goal. Benchmarks, not tests: the figures
# never fail the run. Instruction counts are exact (callgrind on the host,
# QEMU's instruction counting on the MCUs), so they repeat run to run.
#
#   x86-64 control tick      callgrind, bench_board (trot, turn, body pose)
#   fixed vs double IK       callgrind, bench_kinematics
#   parser per byte          callgrind, bench_parser parser (1 MiB mixed stream)
#   Cortex-M0 / M3 tick      tools/mcu/run.sh (QEMU micro:bit / mps2-an385), the
#                            full core and the firmware configuration
#   firmware flash, RAM      tools/mcu/fw_check.sh on both images (ports/template
#                            built too: it must link)
#   stack                    tools/mcu/run.sh (painted RAM around each call)
#
# Needs valgrind, arm-none-eabi-gcc, qemu-system-arm; HOST_BUILD (default
# build/) must hold the benches (cmake --build build --target bench_board
# bench_kinematics bench_parser).
set -euo pipefail
cd "$(dirname "$0")/.."
host=${1:-build}

collected() { # PROGRAM ARGS...: callgrind's instruction count of the toggled function
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
row() { printf '  %-44s %12s   goal %s\n' "$1" "$2" "$3"; }

cmake --build "$host" -j2 --target bench_board bench_kinematics bench_parser >/dev/null

echo "== x86-64 (gcc, the core at -O3 and -flto as the host build makes it; callgrind)"
a=$(collected --toggle-collect=xgo_board_tick "$host/bench_board" 1000)
b=$(collected --toggle-collect=xgo_board_tick "$host/bench_board" 11000)
row "xgo_board_tick, trot + body pose" "$(((b - a) / 10000))" "<= 5,000"
fixed=$(collected --toggle-collect=bench_fixed_step "$host/bench_kinematics" fixed 10000)
double=$(collected --toggle-collect=bench_double_step "$host/bench_kinematics" double 10000)
row "IK step, fixed point / double (libm)" "$((fixed / 10000)) / $((double / 10000))" \
  "fixed <= double ($(awk -v f="$fixed" -v d="$double" 'BEGIN { printf "%.2f", f / d }') x)"
bytes=$("$host/bench_parser" 1 parser | sed -n 's/.*parser only, \([0-9]*\) bytes.*/\1/p')
parser=$(collected --toggle-collect=xgo_parser_feed "$host/bench_parser" 1 parser)
row "parser, instructions per byte" "$(awk -v p="$parser" -v n="$bytes" 'BEGIN { printf "%.1f", p / n }')" "<= 25"

# Each MCU twice: the core with every feature (the host's configuration) and
# with the firmware images' options and buffers (XGO_MCU_CONFIG=firmware:
# what the STM32/nRF51 images run).
for target in m0 m3; do
  for config in full firmware; do
    out=$(XGO_MCU_TARGET=$target XGO_MCU_CONFIG=$config bash tools/mcu/run.sh 2>&1) ||
      { echo "$out"; exit 1; }
    avg=$(echo "$out" | sed -n 's/.*ticks 1001..2000 (steady): min [0-9]* avg \([0-9.]*\).*/\1/p')
    p99=$(echo "$out" | sed -n 's/.*ticks 1001..2000 (steady): p50.* p99 \([0-9]*\).*/\1/p')
    if [ "$target" = m0 ]; then
      [ "$config" = full ] && echo "== Cortex-M0 (QEMU micro:bit, -Os)"
      row "xgo_board_tick trot + pose, $config, avg / p99" "$avg / $p99" "<= 15,000 / 25,000"
      echo "$out" | grep -E "^INFO sizeof|^COST stack below" | sed 's/^/    /'
    else
      [ "$config" = full ] && echo "== Cortex-M3 (QEMU mps2-an385, -Os)"
      row "xgo_board_tick trot + pose, $config, avg" "$avg" "<= 8,000"
    fi
    echo "$out" | grep '^identical' | sed 's/^/    /'
  done
done

echo "== firmware images (arm-none-eabi-gcc -Os): goal flash <= 20 KiB, board + stack <= 3 KiB"
# The template port too: docs/mcu.md promises that it links as it is.
for port in stm32f1 nrf51 template; do
  dir=build-fw-$port
  [ -f "$dir/CMakeCache.txt" ] ||
    cmake -S . -B "$dir" -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi.cmake -DXGO_PORT="$port" \
      -DCMAKE_BUILD_TYPE=MinSizeRel >/dev/null
  cmake --build "$dir" -j2 >/dev/null
done
echo "  ports/template links: $(arm-none-eabi-size build-fw-template/xgo-fw.elf | awk 'NR == 2 { print $1 + $2 }') bytes of flash"
bash tools/mcu/fw_check.sh build-fw-stm32f1/xgo-fw.elf build-fw-nrf51/xgo-fw.elf
