#!/usr/bin/env bash
# tools/mcu/fw_check.sh ELF... - what a firmware image costs and pulls in
# (docs/mcu.md, "Budgets"). For each image:
#   - flash (text + data) and RAM (data + bss), each by origin (core,
#     libgcc, port; from the link map next to the image), and the device
#     object (the board, its receive ring and the port's bookkeeping: the
#     core's state);
#   - floating point: no soft-float helper (__aeabi_f*/d*, __addsf3, ...)
#     may be linked at all (the core has no float);
#   - 64-bit division helpers (__aeabi_ldivmod, __aeabi_uldivmod, __divdi3,
#     __udivdi3, __udivmoddi4, ...) reachable from xgo_board_tick: found by
#     walking direct calls and tail calls in the disassembly from the tick;
#   - the worst-case stack, a static bound: the frames GCC reports
#     (-fstack-usage: the .su files next to the image's objects, which the
#     firmware build writes) summed along the deepest call path from
#     Reset_Handler, plus the deepest interrupt handler (*_irq; the fault
#     handlers stop the firmware) and the exception frame, 36 bytes: eight
#     words plus one of padding when the stack pointer is not 8-byte aligned
#     (always realigned on ARMv6-M, with CCR.STKALIGN on ARMv7-M). The ports
#     give every interrupt the same priority: none nests. An indirect call (blx/bx
#     through a register) may reach any function whose address is in a
#     literal pool; recursion is cut at the second visit; functions without
#     a .su entry (libgcc, assembly) count 0 bytes (libgcc's helpers the
#     images link push at most a few registers). With link-time optimisation
#     the core's frames are in the .su written at the link (xgo-fw.elf.ltrans*.su).
# Prints one line per figure; exits 1 if an image has a soft-float helper or
# a 64-bit division reachable from the tick, or no xgo_board_tick to walk from. Needs arm-none-eabi binutils.
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

# stack_bound ELF: "MAIN_BYTES MAIN_PATH IRQ_BYTES IRQ_PATH" (see the top).
stack_bound() {
  local elf=$1
  { find "$(dirname "$elf")" -name '*.su' -exec cat {} + 2>/dev/null | sed 's/^/SU\t/'
    arm-none-eabi-objdump -d --no-show-raw-insn "$elf"; } | awk -F'\n' '
    function hex(h,   i, v) { # mawk has no strtonum
      h = tolower(h); sub(/^0x/, "", h); v = 0
      for (i = 1; i <= length(h); i++) v = v * 16 + index("0123456789abcdef", substr(h, i, 1)) - 1
      return v
    }
    function frame(f,   b) { # a clone "f.isra.0" is "f.isra" in the .su, "f.lto_priv.0" is "f"
      if (f in su) return su[f]
      b = f; sub(/\.[0-9]+$/, "", b)
      if (b in su) return su[b]
      b = f; sub(/\..*/, "", b)
      return (b in su) ? su[b] : 0
    }
    function deep(f,   n, i, g, d, best, bestp, out) {
      if (f in memo) return memo[f]
      if (onstack[f]) return 0
      onstack[f] = 1
      best = 0; bestp = ""
      n = split(edge[f], out, " ")
      for (i = 1; i <= n; i++) {
        g = out[i]
        d = deep(g)
        if (d > best) { best = d; bestp = path[g] }
      }
      if (indirect[f]) for (g in taken) if (!onstack[g]) {
        d = deep(g)
        if (d > best) { best = d; bestp = path[g] }
      }
      onstack[f] = 0
      memo[f] = frame(f) + best
      path[f] = f "(" frame(f) ")" (bestp == "" ? "" : " > " bestp)
      return memo[f]
    }
    /^SU\t/ { split($0, c, "\t"); n = split(c[2], loc, ":"); name = loc[n]
               if (!(name in su) || c[3] + 0 > su[name]) su[name] = c[3] + 0; next }
    /^[0-9a-f]+ <[^>]+>:$/ { fn = $0; sub(/^[0-9a-f]+ </, "", fn); sub(/>:$/, "", fn)
                             start[fn] = hex(substr($0, 1, index($0, " ") - 1)); next }
    fn != "" && match($0, /\t(bl|b|b\.w|b\.n)[ \t]+[0-9a-f]+ <[^>+]+>/) {
      t = substr($0, RSTART, RLENGTH); sub(/.*</, "", t); sub(/>.*/, "", t)
      if (t != fn) edge[fn] = edge[fn] " " t
      next
    }
    fn != "" && /\t(blx|bx)[ \t]+r[0-9]+$/ { indirect[fn] = 1; next }
    fn != "" && match($0, /\.word[ \t]+0x[0-9a-f]+/) { words[substr($0, RSTART + 6)] = 1 }
    END {
      for (w in words) { v = hex(w); if (v % 2 == 1) addr[v - 1] = 1 }
      for (f in start) if (start[f] in addr) taken[f] = 1
      main = deep("Reset_Handler"); mainp = path["Reset_Handler"]
      irq = 0; irqp = "none"
      for (f in start) if (f ~ /_irq$/) {
        d = deep(f); if (d > irq) { irq = d; irqp = path[f] }
      }
      print main "\t" mainp "\t" irq "\t" irqp
    }'
}

status=0
frame=36 # the exception frame (see the top)
for elf in "$@"; do
  echo "== $elf"
  read -r text data bss _ < <(arm-none-eabi-size "$elf" | tail -n 1)
  device=$(arm-none-eabi-nm -S "$elf" | awk '$4 == "device" { print $2 }')
  [ -n "$device" ] && device=$((16#$device))
  printf '  flash %d bytes (%s KiB), RAM %d bytes (data %d, bss %d); device object %s bytes\n' \
    $((text + data)) "$(awk -v b=$((text + data)) 'BEGIN { printf "%.1f", b / 1024 }')" \
    $((data + bss)) "$data" "$bss" "${device:-?}"
  # By origin: the core (its library, or the units link-time optimisation
  # made of it), libgcc, the port with its start-up code.
  map=$(dirname "$elf")/xgo-fw.map
  [ -f "$map" ] && awk -v core='libxgo_core\\.a|ltrans[0-9]*\\.ltrans\\.o' -v other=port \
    -f "$(dirname "$0")/map_sizes.awk" "$map" | sed 's/^/  /'

  if [ -n "$(find "$(dirname "$elf")" -name '*.su' -print -quit)" ]; then # no early-closed pipe under pipefail
    IFS=$'\t' read -r main mainp irq irqp < <(stack_bound "$elf")
    printf '  stack bound %d bytes: main loop %d + interrupt %d + exception frame %d (static, -fstack-usage)\n' \
      $((main + irq + frame)) "$main" "$irq" "$frame"
    echo "    deepest: $mainp"
    echo "    interrupt: $irqp"
    [ -n "$device" ] && printf '  device object + stack bound: %d bytes\n' $((device + main + irq + frame))
  else
    echo "  stack bound: no .su files next to the image (build with -fstack-usage)"
  fi
  floats=$(arm-none-eabi-nm "$elf" | awk '{ print $NF }' | grep -E "$soft_float" || true)
  if [ -n "$floats" ]; then
    echo "  FAIL soft-float helpers linked: $(echo $floats)"
    status=1
  else
    echo "  no soft-float helper linked"
  fi
  if ! grep -qE ' [Tt] xgo_board_tick$' <<<"$(arm-none-eabi-nm "$elf")"; then
    # Inlined away (link-time optimisation without ports/CMakeLists.txt's
    # --undefined): the walk below would prove nothing.
    echo "  FAIL xgo_board_tick is not a function of the image: nothing to walk from"
    status=1
    continue
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
