#!/usr/bin/env bash
# tools/mcu/fw_stack.sh MONITOR ELF - the deepest stack a running firmware
# has used so far, read from the target's RAM (docs/mcu.md, "Budgets").
#
# The firmware's start-up code paints the RAM between the end of .bss and
# the stack pointer with a pattern (ports/cortex-m/startup.c); the stack
# grows down into it, interrupts included. This asks QEMU's monitor
# (tools/mcu/serve.sh --monitor MONITOR) to dump that RAM and finds the
# lowest word that is no longer the pattern. Run it after a workload.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: tools/mcu/fw_stack.sh MONITOR ELF" >&2; exit 2; }
mon=$1 elf=$2
sym() { arm-none-eabi-nm "$elf" | awk -v s="$1" '$3 == s { print $1 }'; }
ebss=$((16#$(sym _ebss)))
estack=$((16#$(sym _estack)))
len=$((estack - ebss))
dump=$(mktemp "${TMPDIR:-/tmp}/xgo-fw-ram.XXXXXX")
# The monitor echoes what it is sent: drain its output meanwhile.
timeout 10 cat "$mon.out" >/dev/null &
drain=$!
trap 'rm -f "$dump"; kill "$drain" 2>/dev/null || true' EXIT
: >"$dump"
printf 'pmemsave 0x%x %d "%s"\n' "$ebss" "$len" "$dump" >"$mon.in"
for _ in $(seq 100); do
  [ "$(stat -c %s "$dump")" -ge "$len" ] && break
  sleep 0.05
done
[ "$(stat -c %s "$dump")" -ge "$len" ] || { echo "fw_stack.sh: QEMU's monitor did not dump the RAM" >&2; exit 1; }
# awk reads to the end (no early exit): od must not meet a closed pipe, which
# under pipefail fails the script once the dump outgrows od's first write.
untouched=$(od -An -v -tx4 -w4 "$dump" | awk 'seen || $1 != "5ac3a55c" { seen = 1; next } { n++ } END { print n * 4 }')
echo "stack: deepest use $((len - untouched)) bytes (RAM above .bss: $len bytes, never touched: $untouched)"
