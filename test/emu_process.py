"""The one way the Python tests stop a process they started (xgo-emu, or
anything else with a stderr file to close): politely first, then by force,
so a hung emulator cannot hang CI."""

import subprocess

STOP_TIMEOUT_S = 5


class EmuProcess:
    """Base for the tests' emulator wrappers: set self.proc (a Popen) and
    self.err (its open stderr file) in __init__."""

    proc = None
    err = None

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.err.close()
        return self.proc.returncode
