#!/usr/bin/env bash
# tools/mcu/profile.sh - where the self test's instructions go on the
# Cortex-M0: builds the image (run.sh), runs it once more in QEMU with a TCG
# plugin counting executions per address (qemu_pc_count.c) and prints a flat
# profile, the callers of the hot helpers and the instruction mix / cycle
# estimate (profile.py). Not part of CI. Needs python3. The profile covers the
# whole self test (about 7,200 board ticks of several kinds; ticks are > 99 %).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${XGO_MCU_BUILD:-build-mcu}
bash tools/mcu/run.sh >/dev/null
gcc -std=c99 -Wall -Wextra -Werror -pedantic -shared -fPIC -O2 tools/mcu/qemu_pc_count.c \
  -o "$out/libpccount.so"
timeout 120 qemu-system-arm -M microbit -display none -monitor none -serial none \
  -icount shift=8 -semihosting-config enable=on,target=native \
  -plugin "$out/libpccount.so,out=$out/pc_counts.txt" -kernel "$out/mcu_selftest.elf" >/dev/null 2>&1
python3 tools/mcu/profile.py "$out/mcu_selftest.elf" "$out/pc_counts.txt" "${1:-25}"
