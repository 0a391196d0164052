#!/usr/bin/env bash
# readme_examples.sh: runs the README's shell examples (its ```sh blocks), in
# order, as a newcomer pasting them would, against a fresh xgo-emu. Proves the
# README's commands work and print what it says they print.
#
#   .ci/readme_examples.sh [README.md]      (from the repository root)
#
# Rules:
#   - a block that runs xgo-emu in the foreground (it serves until Ctrl-C) is
#     started in the background; the next blocks run once its --link path
#     exists, and it is stopped (SIGINT, must exit 0) at the end;
#   - the test command block is skipped: CI's first step runs the same line;
#   - every other block must exit 0 within 5 minutes;
#   - a "# -> TEXT" line in a block is a line the block must print (each one,
#     in order; other output may come in between);
#   - where the machine cannot (a `pip install` fails: no network), the blocks
#     that use what it would have installed are skipped with a note.
# Exit status 0 when every block that ran did what the README says, 1 if not.
set -uo pipefail
readme=${1:-README.md}
work=build/readme-examples
rm -rf "$work" && mkdir -p "$work"

# Split the ```sh blocks into $work/NN.sh.
awk -v dir="$work" '
  /^```sh$/ { n++; file = sprintf("%s/%02d.sh", dir, n); inside = 1; next }
  /^```/ && inside { inside = 0; close(file); next }
  inside { print > file }
' "$readme"

emu_pid=
# The emulator block runs in its own process group: SIGINT reaches xgo-emu
# itself, as Ctrl-C in a terminal would.
cleanup() { [ -n "$emu_pid" ] && kill -INT -- "-$emu_pid" 2>/dev/null; }
trap cleanup EXIT

# The path after --link in a block.
link_of() { grep -o -- '--link [^ ]*' "$1" | head -n1 | cut -d' ' -f2; }

# Checks that every "# -> TEXT" line of block $1 appears in output $2, in order.
check_output() {
  local want line found
  local -a got
  mapfile -t got < "$2"
  local at=0
  while IFS= read -r want; do
    found=0
    while [ "$at" -lt "${#got[@]}" ]; do
      line=${got[$at]}
      at=$((at + 1))
      if [ "$line" = "$want" ]; then found=1; break; fi
    done
    if [ "$found" = 0 ]; then
      echo "  expected the line: $want"
      return 1
    fi
  done < <(sed -n 's/^# -> //p' "$1")
}

start_emulator() {
  local block=$1 link
  link=$(link_of "$block")
  setsid bash "$block" > "$block.out" 2>&1 &
  emu_pid=$!
  for _ in $(seq 600); do # the block may build first: up to 60 s
    [ -L "$link" ] && return 0
    kill -0 "$emu_pid" 2>/dev/null || break
    sleep 0.1
  done
  echo "  xgo-emu did not create $link:"; sed 's/^/    /' "$block.out"
  return 1
}

failed=0
no_pip=0
for block in "$work"/*.sh; do
  name="README block $(basename "$block" .sh)"
  if grep -q 'ctest --test-dir build' "$block"; then
    echo "$name: skipped (the test command: CI's first step runs it)"
    continue
  fi
  if grep -q 'xgo-emu --link' "$block" && ! grep -q '&$' "$block"; then
    echo "$name: starting the emulator in the background"
    start_emulator "$block" || failed=1
    continue
  fi
  if [ "$no_pip" = 1 ] && grep -q 'venv' "$block"; then
    echo "$name: skipped (what it needs could not be installed)"
    continue
  fi
  if timeout 300 bash -e "$block" > "$block.out" 2>&1; then
    if check_output "$block" "$block.out"; then
      echo "$name: ok"
      continue
    fi
  elif grep -q 'pip install' "$block"; then
    echo "$name: pip install failed (no network?); the blocks that need it are skipped"
    sed 's/^/    /' "$block.out" | tail -n 3
    no_pip=1
    continue
  fi
  echo "$name: FAILED"; sed 's/^/    | /' "$block"; echo "  output:"; sed 's/^/    /' "$block.out"
  failed=1
done

if [ -n "$emu_pid" ]; then
  kill -INT -- "-$emu_pid"
  if ! wait "$emu_pid"; then
    echo "xgo-emu did not exit 0 after SIGINT"; failed=1
  fi
  emu_pid=
fi
[ "$failed" = 0 ] && echo "README examples: all ran as documented"
exit "$failed"
