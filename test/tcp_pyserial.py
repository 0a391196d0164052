#!/usr/bin/env python3
"""tcp_pyserial.py XGO_EMU: xgo-emu --tcp with pyserial's socket:// client,
the way a host on Windows, macOS, a container or a VM would reach it.

    python3 test/tcp_pyserial.py build/xgo-emu          # needs pyserial

Checks: the reply bytes to a read through serial_for_url("socket://..."),
a write reaching the board, a second client refused while the first is
connected, the next client served after the first closed. Exit 0 when all
pass, 1 when any fails, 77 (ctest's SKIP_RETURN_CODE) without pyserial.
"""

import os
import select
import socket
import subprocess
import sys
import time

try:
    import serial
except ImportError as exc:  # pragma: no cover - depends on the machine
    print(f"SKIP: pyserial not importable ({exc}); pip install pyserial", file=sys.stderr)
    sys.exit(77)

READ_VX = bytes.fromhex("55 00 09 02 30 01 c3 00 aa")
REPLY_VX_80 = bytes.fromhex("55 00 09 12 30 80 34 00 aa")
WRITE_VX_FF = bytes.fromhex("55 00 09 00 30 ff c7 00 aa")
REPLY_VX_FF = bytes.fromhex("55 00 09 12 30 ff b5 00 aa")


def start(exe):
    proc = subprocess.Popen([exe, "--tcp", "0"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    text = b""
    deadline = time.time() + 5
    while text.count(b"\n") < 2 and time.time() < deadline:
        ready, _, _ = select.select([proc.stdout], [], [], 0.5)
        if ready:
            text += os.read(proc.stdout.fileno(), 4096)
    lines = text.decode().split("\n")
    if len(lines) < 2 or not lines[1].startswith("tcp: 127.0.0.1:"):
        proc.kill()
        raise RuntimeError("no 'tcp: HOST:PORT' line after the pty line: %r" % lines)
    return proc, "socket://" + lines[1][len("tcp: "):]


def main():
    proc, url = start(sys.argv[1])
    failures = []

    def check(name, got, want):
        ok = got == want
        print("%s %s%s" % ("PASS" if ok else "FAIL", name, "" if ok else ": got %r, want %r" % (got, want)))
        if not ok:
            failures.append(name)

    try:
        port = serial.serial_for_url(url, timeout=1)
        port.write(READ_VX)
        check("read over socket://", port.read(9), REPLY_VX_80)
        port.write(WRITE_VX_FF + READ_VX)
        check("write then read", port.read(9), REPLY_VX_FF)
        host, number = url[len("socket://"):].split(":")
        second = socket.create_connection((host, int(number)), timeout=1)
        check("second client refused", second.recv(100), b"xgo-emu: busy, one client at a time\r\n")
        second.close()
        port.close()
        time.sleep(0.1)
        port = serial.serial_for_url(url, timeout=1)
        port.write(READ_VX)
        check("next client served", port.read(9), REPLY_VX_FF)
        port.close()
    finally:
        proc.terminate()
        proc.wait(5)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
