#!/usr/bin/env bash
# tools/mcu/unit_tests.sh [HOST_BUILD] - the core's OS-free Unity suites on
# an emulated Cortex-M: the core built for the Cortex-M3 (the STM32 port's
# CPU, -mcpu=cortex-m3, no floating point), each suite required to end with
# the same summary line ("N Tests F Failures I Ignored") and exit status as
# on the host (docs/testing.md).
#
# The suites' own code - Unity, the double-precision references they
# compare the core with (libm) - is built for a Cortex-M7 with its double
# FPU and the whole image runs on QEMU's mps2-an500 (Cortex-M7, which runs
# the M3 code unchanged): soft-float references made the run take over half
# an hour (test_kinematics alone > 10 min); with the FPU it takes minutes.
#
# Which suites: those the host build (HOST_BUILD, default build/) links
# against nothing but the core, the in-process test helpers
# (test/support/board_io.c, reference.c), the Unity harness and libm - read
# from their link lines, so a new suite is picked up without a list here.
# On the target they link newlib (nano, semihosting through librdimon: stdout
# and exit status reach the host) with our own start-up
# (tools/mcu/unit_startup.c) and libm; the core itself still needs none of it.
# Each run: `time` per suite is printed; the objects are kept in
# $XGO_MCU_UNIT_BUILD (default build-mcu-unit) and rebuilt when newer.
set -euo pipefail
cd "$(dirname "$0")/../.."
host=${1:-build}
out=${XGO_MCU_UNIT_BUILD:-build-mcu-unit}
mcu=tools/mcu
mkdir -p "$out"

suites=()
for dir in "$host"/test/CMakeFiles/test_*.dir; do
  name=$(basename "$dir" .dir)
  link="$dir/link.txt"
  [ -f "$link" ] || continue
  objs=$(tr ' ' '\n' <"$link" | grep '\.o$' || true)
  libs=$(tr ' ' '\n' <"$link" | grep -E '\.a$|^-l' | sed 's|.*/||' | sort -u | tr '\n' ' ')
  [ "$objs" = "CMakeFiles/$name.dir/$name.c.o" ] || continue
  extra=$(echo "$libs" | tr ' ' '\n' | grep -vE '^(libxgo_core\.a|libxgo_assert_hosted\.a|libxgo_test_board\.a|libxgo_test_board_unity\.a|libxgo_test_reference\.a|libxgo_unity\.a|-lm|)$' || true)
  [ -z "$extra" ] || continue
  [ -f "test/$name.c" ] && suites+=("$name")
done
[ ${#suites[@]} -gt 0 ] || { echo "unit_tests.sh: no suites found in $host (build it first)"; exit 1; }

m3=(-mcpu=cortex-m3 -mthumb)
m7=(-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=softfp -D_DEFAULT_SOURCE) # M_PI as on the host
cflags=(-O2 -g -std=c99 -Wall -Wextra -Werror -pedantic -ffunction-sections -fdata-sections
  -Iinclude -Isrc/core -Itest/unity -Itest/support --specs=nano.specs)
echo "== build: ${#suites[@]} suites; the core for a Cortex-M3 (${m3[*]} -O2), the tests for a Cortex-M7 with FPU, newlib-nano + rdimon"
common=()
compile() { # SOURCE CPU-FLAGS...: object file, rebuilt when the source is newer
  local src=$1 obj
  shift
  obj="$out/$(echo "$src" | tr '/' '_' | sed 's/\.c$/.o/')"
  if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ]; then
    arm-none-eabi-gcc "$@" "${cflags[@]}" -c "$src" -o "$obj"
  fi
  common+=("$obj")
}
for src in src/core/*.c; do compile "$src" "${m3[@]}"; done
for src in test/unity/unity.c test/support/board_io.c test/support/board_unity.c test/support/reference.c "$mcu/unit_startup.c"; do
  compile "$src" "${m7[@]}"
done
# The hosted check hook as on the host: an archive, so a suite's own wins.
arm-none-eabi-gcc "${m7[@]}" "${cflags[@]}" -c src/host/assert_hosted.c -o "$out/assert_hosted.o"
rm -f "$out/libassert_hosted.a" && arm-none-eabi-ar rcs "$out/libassert_hosted.a" "$out/assert_hosted.o"

qemu_run() { # ELF: runs it, stdout = the program's output, status = its exit status
  timeout 600 qemu-system-arm -M mps2-an500 -display none -monitor none -serial none \
    -semihosting-config enable=on,target=native -kernel "$1"
}

fail=0
printf '%-20s %-32s %-32s\n' suite host "target (QEMU mps2-an500)"
for s in "${suites[@]}"; do
  elf="$out/$s.elf"
  arm-none-eabi-gcc "${m7[@]}" "${cflags[@]}" -c "test/$s.c" -o "$out/$s.o"
  arm-none-eabi-gcc "${m7[@]}" --specs=nano.specs --specs=rdimon.specs -nostartfiles \
    -T "$mcu/unit.ld" -Wl,--gc-sections -u _printf_float "$out/$s.o" "${common[@]}" "$out/libassert_hosted.a" -lm -o "$elf"
  "$host/test/$s" >"$out/$s.host.out" 2>&1 && hrc=0 || hrc=$?
  qemu_run "$elf" >"$out/$s.mcu.out" 2>&1 && mrc=0 || mrc=$?
  hsum=$(grep -E '^[0-9]+ Tests [0-9]+ Failures [0-9]+ Ignored' "$out/$s.host.out" | tail -n 1 | sed "s/ *$//" || true)
  msum=$(grep -E '^[0-9]+ Tests [0-9]+ Failures [0-9]+ Ignored' "$out/$s.mcu.out" | tail -n 1 | sed "s/ *$//" || true)
  printf '%-20s %-32s %-32s\n' "$s" "${hsum:-none} (exit $hrc)" "${msum:-none} (exit $mrc)"
  if [ -z "$msum" ] || [ "$hsum" != "$msum" ] || [ "$hrc" != "$mrc" ]; then
    echo "FAIL $s: target output in $out/$s.mcu.out"
    grep -E ':FAIL|FAULT' "$out/$s.mcu.out" | head -n 10 || true
    fail=1
  fi
done
[ "$fail" = 0 ] && echo "identical: ${#suites[@]} suites end with the same counts and exit status on the host and the target"
exit "$fail"
