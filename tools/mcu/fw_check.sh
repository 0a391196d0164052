#!/usr/bin/env bash
# tools/mcu/fw_check.sh ELF... - what a firmware image costs and pulls in
# (docs/mcu.md, "Budgets"). For each image:
#   - flash (text + data) and RAM (data + bss), and the device object (the
#     board, its receive ring and the port's bookkeeping: the core's state);
#   - floating point: no soft-float helper (__aeabi_f*/d*, __addsf3, ...)
#     may be linked at all (the core has no float);
#   - 64-bit division helpers (__aeabi_ldivmod, __aeabi_uldivmod, __divdi3,
#     __udivdi3, __udivmoddi4, ...) reachable from xgo_board_tick: found by
#     walking direct calls and tail calls in the disassembly from the tick.
# Prints one line per figure; exits 1 if an image has a soft-float helper or
# a 64-bit division reachable from the tick. Needs arm-none-eabi binutils.
set -euo pipefail

soft_float='^(__aeabi_[fd][a-z0-9]+|__(add|sub|mul|div|neg|cmp|eq|ne|lt|le|gt|ge|un|fix|fixuns|float|floatun|extend|trunc)[sdx]f[0-9a-z]*|__aeabi_[ui]?[lf]2[fd]|__aeabi_[fd]2[a-z]+)$'
div64='^(__aeabi_u?ldivmod|__u?divdi3|__u?moddi3|__udivmoddi4|__divmoddi4|__gnu_uldivmod_helper|__gnu_ldivmod_helper)$'

# reachable PATTERN FUNCTION...: the functions reachable from the given ones
# through direct calls (bl) and branches to the start of another function,
# one per line; those matching PATTERN (a regex) as "HELPER <- CALLER...".
reachable() {
  local pattern=$1
  shift
  arm-none-eabi-objdump -d --no-show-raw-insn "$elf" | awk -v roots="$*" -v pat="$pattern" '
    /^[0-9a-f]+ <[^>]+>:$/ { fn = $2; gsub(/[<>:]/, "", fn); next }
    fn != "" && match($0, /\t(bl|blx|b|b\.w|b\.n|beq|bne|bcs|bcc|bhi|bls|bge|blt|bgt|ble|bmi|bpl|beq\.w|bne\.w)[ \t]+[0-9a-f]+ <[^>+]+>/) {
      t = substr($0, RSTART, RLENGTH); sub(/.*</, "", t); sub(/>.*/, "", t)
      if (t != fn) edge[fn] = edge[fn] " " t
    }
    END {
      n = split(roots, stack, " ")
      for (i = 1; i <= n; i++) seen[stack[i]] = 1
      while (n > 0) {
        f = stack[n--]
        m = split(edge[f], out, " ")
        for (j = 1; j <= m; j++) if (!(out[j] in seen)) { seen[out[j]] = 1; stack[++n] = out[j] }
      }
      for (f in seen) {
        if (f !~ pat) { print f; continue }
        callers = ""
        for (g in seen) if ((" " edge[g] " ") ~ (" " f " ") && g !~ pat) callers = callers " " g
        print f " <-" callers
      }
    }'
}

status=0
for elf in "$@"; do
  echo "== $elf"
  read -r text data bss _ < <(arm-none-eabi-size "$elf" | tail -n 1)
  device=$(arm-none-eabi-nm -S "$elf" | awk '$4 == "device" { print $2 }')
  [ -n "$device" ] && device=$((16#$device))
  printf '  flash %d bytes (%s KiB), RAM %d bytes (data %d, bss %d); device object %s bytes\n' \
    $((text + data)) "$(awk -v b=$((text + data)) 'BEGIN { printf "%.1f", b / 1024 }')" \
    $((data + bss)) "$data" "$bss" "${device:-?}"
  floats=$(arm-none-eabi-nm "$elf" | awk '{ print $NF }' | grep -E "$soft_float" || true)
  if [ -n "$floats" ]; then
    echo "  FAIL soft-float helpers linked: $(echo $floats)"
    status=1
  else
    echo "  no soft-float helper linked"
  fi
  from_tick=$(reachable "$div64" xgo_board_tick)
  divs=$(echo "$from_tick" | grep -E "${div64%\$} <-" || true)
  if [ -n "$divs" ]; then
    echo "  FAIL 64-bit division reachable from xgo_board_tick:"
    echo "$divs" | sed 's/^/    /'
    status=1
  else
    echo "  no 64-bit division reachable from xgo_board_tick ($(echo "$from_tick" | wc -l) functions)"
  fi
done
exit $status
