#!/usr/bin/env python3
"""test_view_browser.py - the view page in a real browser (issue 7).

    test_view_browser.py XGO_EMU [CHROMIUM]

Starts `XGO_EMU --view 127.0.0.1:0`, makes the dog trot as a host on the pty
would (a write frame vx = 0xFF, encoded here), opens the page in headless
Chromium and, through the DevTools protocol on a pipe (--remote-debugging-pipe:
no port, no extra library), checks that the page
  - connected and drew the robot: framesDrawn > 0, the body and the shank
    colours are on the canvas, and the legs drawn by the page's own leg FK
    agree with the core's feet_mm (data-fk-error-mm);
  - moved: two screenshots of the canvas a second apart differ, framesDrawn
    grew and lastStateMs advanced;
  - drives the robot through POST /command: a click on "lie down" starts
    action 1, the S key makes the commanded vx negative and its release zero
    (GET /state); the ground-roll slider tilts the IMU (POST /input);
  - shows a lost connection and reconnects by itself when xgo-emu restarts;
  - threw no uncaught JavaScript exception all along.

Exit 0 pass, 1 fail, 77 skip (no Chromium: ctest SKIP_RETURN_CODE). Waits are
bounded; timings are never asserted (rAF is throttled headless, docs/testing.md).
Python standard library only.
"""
import base64
import json
import os
import select
import shutil
import struct
import subprocess
import sys
import tempfile
import termios
import time
import tty
import urllib.request
import zlib

SKIP = 77


class Failure(Exception):
    pass


def check(cond, what):
    if not cond:
        raise Failure(what)
    print("ok:", what)


def wait_for(what, fn, timeout=15.0, step=0.1):
    """Polls fn until it returns a true value; that value, else Failure."""
    end = time.monotonic() + timeout
    while True:
        value = fn()
        if value:
            return value
        if time.monotonic() > end:
            raise Failure("timed out waiting for " + what)
        time.sleep(step)


# ------------------------------------------------------------ xgo-emu

def frame(addr, data):
    """A write frame as docs/protocol.md defines it (independent of the core's
    encoder): 55 00 LEN TYPE ADDR DATA CHK 00 AA, LEN = n + 8, TYPE 0x00 write,
    CHK = ~(LEN + TYPE + ADDR + DATA) & 0xFF."""
    body = [8 + len(data), 0x00, addr] + list(data)
    return bytes([0x55, 0x00] + body + [~sum(body) & 0xFF, 0x00, 0xAA])


class Emulator:
    def __init__(self, exe, listen, *extra):
        self.proc = subprocess.Popen([exe, "--view", listen] + list(extra), stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL)
        self.out = b""
        self.fd = None
        try:
            self.pty = self._line("pty path")
            view = self._line("view line")
            if not view.startswith("view: http://") or not view.endswith("/"):
                raise Failure("unexpected view line: " + view)
            self.url = view[len("view: "):]
            self.port = int(self.url.rsplit(":", 1)[1].strip("/"))
        except Failure:
            self.stop()  # never leave a half-started emulator behind
            raise

    def _line(self, what):
        """The next stdout line (raw reads: a buffered reader would hide the
        second line from select)."""
        end = time.monotonic() + 10
        while b"\n" not in self.out:
            ready, _, _ = select.select([self.proc.stdout], [], [], max(end - time.monotonic(), 0))
            chunk = os.read(self.proc.stdout.fileno(), 4096) if ready else b""
            if not chunk:
                raise Failure("xgo-emu printed no " + what + " (exit %s)" % self.proc.poll())
            self.out += chunk
        line, self.out = self.out.split(b"\n", 1)
        return line.decode().strip()

    def host_write(self, addr, data):
        if self.fd is None:
            self.fd = os.open(self.pty, os.O_RDWR | os.O_NOCTTY)
            tty.setraw(self.fd)
            termios.tcflush(self.fd, termios.TCIOFLUSH)
        os.write(self.fd, frame(addr, data))

    def state(self):
        with urllib.request.urlopen(self.url + "state", timeout=5) as r:
            return json.loads(r.read())

    def stop(self):
        if self.fd is not None:
            os.close(self.fd)
            self.fd = None
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()


# ------------------------------------------------------------ Chromium

class Browser:
    """Headless Chromium driven over --remote-debugging-pipe: JSON messages
    separated by NUL, Chromium reads fd 3 and writes fd 4."""

    def __init__(self, exe, profile_dir):
        to_chrome_r, self.to_chrome = os.pipe()
        self.from_chrome, from_chrome_w = os.pipe()

        def fds():
            a, b = os.dup(to_chrome_r), os.dup(from_chrome_w)
            os.dup2(a, 3)
            os.dup2(b, 4)

        self.proc = subprocess.Popen(
            [exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
             "--disable-component-update", "--disable-sync", "--no-first-run",
             "--remote-debugging-pipe", "--user-data-dir=" + profile_dir, "--window-size=1280,800",
             "about:blank"],
            preexec_fn=fds, close_fds=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self.buf = b""
        self.next_id = 0
        self.session = None
        self.errors = []  # uncaught JavaScript exceptions seen

    def call(self, method, params=None, session=True, timeout=20.0):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self.to_chrome, json.dumps(msg).encode() + b"\0")
        end = time.monotonic() + timeout
        while True:
            while b"\0" not in self.buf:
                left = end - time.monotonic()
                ready, _, _ = select.select([self.from_chrome], [], [], max(left, 0))
                if not ready:
                    raise Failure("Chromium did not answer " + method)
                chunk = os.read(self.from_chrome, 1 << 20)
                if not chunk:
                    raise Failure("Chromium closed the pipe during " + method)
                self.buf += chunk
            raw, self.buf = self.buf.split(b"\0", 1)
            reply = json.loads(raw)
            if reply.get("method") == "Runtime.exceptionThrown":  # an uncaught error in the page
                details = reply["params"]["exceptionDetails"]
                self.errors.append(details.get("exception", {}).get("description") or details.get("text"))
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise Failure(method + ": " + json.dumps(reply["error"]))
                return reply["result"]

    def open(self, url):
        target = self.call("Target.createTarget", {"url": url}, session=False)["targetId"]
        self.session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True},
                                 session=False)["sessionId"]
        self.call("Runtime.enable")  # reports uncaught exceptions from here on

    def eval(self, expr):
        r = self.call("Runtime.evaluate", {"expression": expr, "returnByValue": True})
        return r["result"].get("value")

    def dataset(self):
        return self.eval("Object.assign({}, document.body.dataset)") or {}

    def screenshot(self, clip):
        r = self.call("Page.captureScreenshot", {"format": "png", "clip": dict(clip, scale=1)})
        return base64.b64decode(r["data"])

    def key(self, kind, code, key):
        self.call("Input.dispatchKeyEvent", {"type": kind, "code": code, "key": key,
                                             "windowsVirtualKeyCode": ord(key.upper())})

    def close(self):
        try:
            self.call("Browser.close", session=False, timeout=5)
        except (Failure, OSError):
            pass
        try:
            self.proc.wait(5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        os.close(self.to_chrome)
        os.close(self.from_chrome)


# ------------------------------------------------------------ PNG

def png_pixels(data):
    """(width, height, rows of RGB tuples) of an 8-bit RGB/RGBA PNG."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise Failure("not a PNG")
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or color not in (2, 6) or interlace:
                raise Failure("unexpected PNG format")
            bpp = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, prev, rows = zlib.decompress(idat), width * bpp, bytearray(width * bpp), []
    for y in range(height):
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        unfilter(raw[y * (stride + 1)], line, prev, bpp)
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def unfilter(kind, line, prev, bpp):
    for i in range(len(line)):
        a = line[i - bpp] if i >= bpp else 0
        b = prev[i]
        c = prev[i - bpp] if i >= bpp else 0
        if kind == 1:
            line[i] = (line[i] + a) & 0xFF
        elif kind == 2:
            line[i] = (line[i] + b) & 0xFF
        elif kind == 3:
            line[i] = (line[i] + (a + b) // 2) & 0xFF
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else (b if pb <= pc else c))) & 0xFF


def count_near(rows, rgb, tol):
    return sum(1 for row in rows for p in row
               if abs(p[0] - rgb[0]) <= tol and abs(p[1] - rgb[1]) <= tol and abs(p[2] - rgb[2]) <= tol)


def differing(rows_a, rows_b):
    return sum(1 for ra, rb in zip(rows_a, rows_b) for pa, pb in zip(ra, rb) if pa != pb)


# ------------------------------------------------------------ the test

SHANK = (0xE8, 0xA3, 0x3D)  # view.js SEGMENT_STYLE: only the shanks have this colour


def check_drawing(browser):
    ds = wait_for("the first robot frame", lambda: (lambda d: d if int(d.get("framesDrawn", "0")) > 0
                                                   else None)(browser.dataset()))
    check(ds.get("connected") == "1", "page connected (data-connected=1)")
    rect = browser.eval("(function(){var r=document.getElementById('scene').getBoundingClientRect();"
                        "return {x:r.left,y:r.top,width:r.width,height:r.height};})()")
    check(rect["width"] > 200 and rect["height"] > 200, "canvas is laid out (%dx%d)" % (rect["width"], rect["height"]))
    first = browser.dataset()
    w, h, rows_a = png_pixels(browser.screenshot(rect))
    shank = count_near(rows_a, SHANK, 40)
    check(shank > 100, "the shanks are drawn (%d pixels of their colour)" % shank)
    fk = float(wait_for("data-fk-error-mm", lambda: browser.dataset().get("fkErrorMm")))
    check(fk < 0.5, "legs from joints_deg via the page's FK match feet_mm (%.3f mm)" % fk)
    time.sleep(1.0)
    second = browser.dataset()
    _, _, rows_b = png_pixels(browser.screenshot(rect))
    diff = differing(rows_a, rows_b)
    check(diff > w * h // 200, "the drawing moved: %d of %d pixels differ" % (diff, w * h))
    check(int(second["framesDrawn"]) > int(first["framesDrawn"]),
          "framesDrawn grew (%s -> %s)" % (first["framesDrawn"], second["framesDrawn"]))
    check(int(second["lastStateMs"]) > int(first["lastStateMs"]),
          "lastStateMs advanced (%s -> %s)" % (first["lastStateMs"], second["lastStateMs"]))
    save_as = os.environ.get("XGO_VIEW_SCREENSHOT")
    if save_as:  # the picture in docs/view.md and the README
        size = browser.eval("[innerWidth, innerHeight]")  # scaled: under 200 KB
        shot = browser.call("Page.captureScreenshot", {"format": "png", "clip": {
            "x": 0, "y": 0, "width": size[0], "height": size[1], "scale": 0.75}})["data"]
        with open(save_as, "wb") as f:
            f.write(base64.b64decode(shot))
        print("saved", save_as)


def check_remote_control(browser, emu):
    browser.eval("document.querySelector('#actions button[data-action=\"1\"]').click()")
    wait_for("action 1 after the click", lambda: emu.state()["action"]["id"] == 1)
    check(True, "a click on 'lie down' started action 1 (POST /command)")
    wait_for("action 1 to end", lambda: emu.state()["action"]["id"] == 0, timeout=20)
    browser.eval("document.activeElement && document.activeElement.blur()")
    browser.key("keyDown", "KeyS", "s")
    vx = wait_for("vx < 0 while S is held", lambda: (lambda v: v if v < 0 else None)(
        emu.state()["speed"]["cmd"]["vx_mm_s"]))
    check(vx < 0, "the S key commands backwards (vx %.0f mm/s)" % vx)
    browser.key("keyUp", "KeyS", "s")
    wait_for("vx = 0 after S is released", lambda: emu.state()["speed"]["cmd"]["vx_mm_s"] == 0)
    check(True, "releasing S commands vx = 0")


def check_inputs(browser, emu):
    browser.eval("(function(){var e=document.getElementById('in-roll'); e.value='10';"
                 "e.dispatchEvent(new Event('input'));})()")
    roll = wait_for("IMU roll after the ground-roll slider", lambda: (lambda r: r if abs(r - 10) < 0.5
                                                                     else None)(emu.state()["imu"]["roll_deg"]))
    check(True, "the ground-roll slider tilts the ground (POST /input): IMU roll %.2f deg" % roll)


def check_reconnect(browser, emu_exe, emu):
    port = emu.port
    emu.stop()
    wait_for("data-connected=0", lambda: browser.dataset().get("connected") == "0", timeout=10)
    check(browser.eval("!document.getElementById('lost').hidden"), "the connection-lost banner shows")
    emu2 = wait_for("xgo-emu back on port %d" % port, lambda: try_start(emu_exe, port), timeout=10, step=0.5)
    try:
        wait_for("data-connected=1 again", lambda: browser.dataset().get("connected") == "1", timeout=15)
        check(browser.eval("document.getElementById('lost').hidden"), "reconnected by itself, banner gone")
    finally:
        emu2.stop()


ARM = (0xD0, 0x5C, 0xE3)  # view.js ARM_COLOR: the Mini2's forearm


def arm_pixels(browser, rect):
    """(count, mean x, mean y) of the forearm's colour in the canvas."""
    _, _, rows = png_pixels(browser.screenshot(rect))
    pts = [(x, y) for y, row in enumerate(rows) for x, p in enumerate(row)
           if abs(p[0] - ARM[0]) <= 30 and abs(p[1] - ARM[1]) <= 30 and abs(p[2] - ARM[2]) <= 30]
    if not pts:
        return 0, 0.0, 0.0
    return len(pts), sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts)


def check_arm(chromium, exe, profile):
    """--profile mini2: the page draws the arm from /state's "arm", and it
    moves when the host moves it (arm(x, z): 0x73/0x74)."""
    emu = Emulator(exe, "127.0.0.1:0", "--profile", "mini2")
    browser = Browser(chromium, profile + "-mini2")
    try:
        browser.open(emu.url)
        wait_for("a mini2 frame", lambda: int(browser.dataset().get("framesDrawn", "0")) > 0)
        rect = browser.eval("(function(){var r=document.getElementById('scene').getBoundingClientRect();"
                            "return {x:r.left,y:r.top,width:r.width,height:r.height};})()")
        n0, x0, y0 = arm_pixels(browser, rect)
        check(n0 > 40, "the Mini2's forearm is drawn (%d pixels of its colour)" % n0)
        emu.host_write(0x73, [0x30])  # x -36 mm: over the back
        emu.host_write(0x74, [0xB0])  # z 78 mm: up
        wait_for("the arm to move", lambda: emu.state()["arm"]["claw_mm"][0] < 60)
        time.sleep(0.5)
        n1, x1, y1 = arm_pixels(browser, rect)
        check(n1 > 40 and abs(x1 - x0) + abs(y1 - y0) > 10,
              "the drawn arm moved with the board's (%.0f,%.0f) -> (%.0f,%.0f)" % (x0, y0, x1, y1))
        check(not browser.errors, "no uncaught JavaScript error with the arm")
    finally:
        browser.close()
        emu.stop()


def try_start(exe, port):
    try:
        return Emulator(exe, "127.0.0.1:%d" % port)
    except Failure:
        return None


def main():
    if len(sys.argv) < 2:
        print("usage: test_view_browser.py XGO_EMU [CHROMIUM]", file=sys.stderr)
        return 2
    chromium = sys.argv[2] if len(sys.argv) > 2 else (shutil.which("chromium") or
                                                       shutil.which("chromium-browser"))
    if not chromium or not os.access(chromium, os.X_OK):
        print("skip: no chromium (apt-get install -y chromium)")
        return SKIP
    profile = tempfile.mkdtemp(prefix="xgo-view-browser-")
    emu = browser = None
    try:
        emu = Emulator(sys.argv[1], "127.0.0.1:0")
        emu.host_write(0x30, [0xFF])  # vx full forward: the dog trots ...
        emu.host_write(0x32, [0xB0])  # ... turning left: an arc
        wait_for("the trot", lambda: emu.state()["speed"]["actual"]["vx_mm_s"] > 50)
        browser = Browser(chromium, profile)
        browser.open(emu.url)
        check_drawing(browser)
        check_remote_control(browser, emu)
        check_inputs(browser, emu)
        check_reconnect(browser, sys.argv[1], emu)
        check_arm(chromium, sys.argv[1], profile)
        check(not browser.errors, "no uncaught JavaScript error (%s)" % "; ".join(map(str, browser.errors)))
        print("view page in Chromium: all checks passed")
        return 0
    except Failure as e:
        print("FAIL:", e)
        return 1
    finally:
        if browser:
            browser.close()
        if emu:
            emu.stop()
        shutil.rmtree(profile, ignore_errors=True)
        shutil.rmtree(profile + "-mini2", ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
