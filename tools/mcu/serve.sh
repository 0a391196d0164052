#!/usr/bin/env bash
# tools/mcu/serve.sh - the board's firmware (ports/) on an emulated MCU in
# QEMU, served on a pseudo-terminal like xgo-emu (docs/mcu.md).
set -uo pipefail

usage() {
  cat <<'EOF'
usage: tools/mcu/serve.sh stm32|nrf51 [options]
Builds the firmware for the chip if needed (ports/stm32f1 or ports/nrf51,
into build-fw-<port>/), runs it in QEMU (stm32vldiscovery or microbit) with
the UART on a pseudo-terminal, prints the pty path as the first line on
stdout and serves until SIGINT/SIGTERM (then stops QEMU, removes the link,
exits 0).

options:
      --link PATH     keep a symlink PATH -> the pty; replaces only a stale pty link
                      (one into the pty directory whose pty is gone); anything else
                      at PATH is refused (exit 1)
      --state FILE    the board's non-volatile data (Bluetooth name, zero offsets) in
                      FILE, QEMU's stand-in for flash (ports/cortex-m/nv_file.h)
      --monitor PATH  QEMU's monitor on the FIFOs PATH.in / PATH.out, created here
                      (tools/mcu/fw_stack.sh reads the stack depth through it)
  -h, --help          show this help and exit

exit status: 0 after SIGINT/SIGTERM, 1 on a runtime error (build, QEMU, link),
2 on misuse.
EOF
}

misuse() {
  echo "serve.sh: $1" >&2
  usage >&2
  exit 2
}

die() {
  echo "serve.sh: $1" >&2
  exit 1
}

root=$(cd "$(dirname "$0")/../.." && pwd)
chip=""; link=""; state=""; monitor=""
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --link|--state|--monitor)
      [ $# -ge 2 ] && [ -n "$2" ] || misuse "$1 needs a value"
      case "$1" in --link) link=$2 ;; --state) state=$2 ;; --monitor) monitor=$2 ;; esac
      shift 2 ;;
    --link=*) link=${1#*=}; [ -n "$link" ] || misuse "--link needs a value"; shift ;;
    --state=*) state=${1#*=}; [ -n "$state" ] || misuse "--state needs a value"; shift ;;
    --monitor=*) monitor=${1#*=}; [ -n "$monitor" ] || misuse "--monitor needs a value"; shift ;;
    -*) misuse "unknown option $1" ;;
    *) [ -z "$chip" ] || misuse "unexpected argument $1"; chip=$1; shift ;;
  esac
done
case "$chip" in
  stm32) port=stm32f1; machine=stm32vldiscovery ;;
  nrf51) port=nrf51; machine=microbit ;;
  "") misuse "which chip: stm32 or nrf51" ;;
  *) misuse "unknown chip $chip (stm32 or nrf51)" ;;
esac
if [ -n "$state" ]; then
  # The path travels in QEMU's option syntax and the firmware's command line.
  case "$state" in *,*|*" "*) misuse "--state: the path may not contain commas or spaces" ;; esac
  state=$(realpath -m -- "$state")
  [ ${#state} -lt 160 ] || misuse "--state: the path is longer than 159 characters"
fi

# ---- build (quiet unless it fails) ----------------------------------------
build=${XGO_FW_BUILD:-$root/build-fw-$port}
elf=$build/xgo-fw.elf
log=$(mktemp -d "${TMPDIR:-/tmp}/xgo-fw-serve.XXXXXX") || die "cannot create a temporary directory"
cleanup_log() { rm -rf "$log"; }
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$root/cmake/arm-none-eabi.cmake" \
    -DXGO_PORT="$port" -DCMAKE_BUILD_TYPE=MinSizeRel >"$log/build" 2>&1 ||
    { cat "$log/build" >&2; cleanup_log; die "configuring the firmware build failed"; }
fi
cmake --build "$build" -j2 >"$log/build" 2>&1 ||
  { cat "$log/build" >&2; cleanup_log; die "building the firmware failed"; }

# ---- QEMU -----------------------------------------------------------------
qemu_pid=""
stopping=0
stop_qemu() {
  if [ -n "$qemu_pid" ] && kill -0 "$qemu_pid" 2>/dev/null; then
    kill -TERM "$qemu_pid" 2>/dev/null
    wait "$qemu_pid" 2>/dev/null
  fi
}
on_signal() {
  stopping=1
  stop_qemu
}
trap on_signal INT TERM HUP
sh_config="enable=on,target=native,arg=xgo-fw"
[ -n "$state" ] && sh_config="$sh_config,arg=$state"
mon=(-monitor none)
if [ -n "$monitor" ]; then
  for f in "$monitor.in" "$monitor.out"; do
    [ -p "$f" ] || mkfifo -m 600 -- "$f" || { cleanup_log; die "--monitor: cannot create the FIFO $f"; }
  done
  mon=(-monitor "pipe:$monitor")
fi
qemu-system-arm -M "$machine" -nographic "${mon[@]}" -serial pty \
  -semihosting-config "$sh_config" -kernel "$elf" >"$log/qemu" 2>&1 &
qemu_pid=$!

pty=""
for _ in $(seq 200); do
  pty=$(sed -n 's|^char device redirected to \(/dev/[^ ]*\) .*|\1|p' "$log/qemu" | head -n 1)
  [ -n "$pty" ] && break
  kill -0 "$qemu_pid" 2>/dev/null || break
  sleep 0.05
done
if [ "$stopping" = 1 ]; then
  cleanup_log
  exit 0
fi
if [ -z "$pty" ]; then
  stop_qemu
  cat "$log/qemu" >&2
  cleanup_log
  die "QEMU did not report its pty"
fi

# ---- the --link symlink (the rules of xgo-emu --link, src/host/link.c) ----
make_link() {
  local old tmp
  if ln -s -- "$pty" "$link" 2>/dev/null; then
    return 0
  fi
  if [ ! -L "$link" ]; then
    if [ -e "$link" ]; then
      echo "serve.sh: --link $link: exists and is not a symlink, refusing to replace it" >&2
    else
      echo "serve.sh: --link $link: cannot create symlink" >&2
    fi
    return 1
  fi
  old=$(readlink -- "$link")
  if [ "$old" != "$pty" ]; then
    # A name directly in our pty's directory (/dev/pts/7 next to /dev/pts/3)?
    rest=${old#"$(dirname "$pty")"/}
    if [ "$rest" = "$old" ] || [ -z "$rest" ] || [[ "$rest" == */* ]]; then
      echo "serve.sh: --link $link: is a symlink to $old, not to a pty; refusing to replace it" >&2
      return 1
    fi
    if [ -e "$link" ]; then
      echo "serve.sh: --link $link: is a symlink to $old, a pty that exists (another emulator or device uses this name); refusing to replace it" >&2
      return 1
    fi
  fi
  # rename() so the name never disappears for a host retrying its open.
  tmp="$link.serve-$$.tmp"
  rm -f -- "$tmp"
  ln -s -- "$pty" "$tmp" && mv -T -- "$tmp" "$link" && return 0
  rm -f -- "$tmp"
  echo "serve.sh: --link $link: cannot replace symlink" >&2
  return 1
}
remove_link() {
  if [ -n "$link" ] && [ -L "$link" ] && [ "$(readlink -- "$link")" = "$pty" ]; then
    rm -f -- "$link"
  fi
}
if [ -n "$link" ] && ! make_link; then
  stop_qemu
  cleanup_log
  exit 1
fi

echo "$pty"

wait "$qemu_pid"
status=$?
while [ "$stopping" = 0 ] && kill -0 "$qemu_pid" 2>/dev/null; do
  wait "$qemu_pid"; status=$?   # woken by a signal we do not trap
done
remove_link
if [ "$stopping" = 1 ]; then
  cleanup_log
  exit 0
fi
sed '/^char device redirected to /d' "$log/qemu" >&2
cleanup_log
die "QEMU exited on its own with status $status (firmware fault: 91, unexpected interrupt: 92)"
