# SPDX-License-Identifier: MIT
"""Start `hilbridge emulate modbus-drive` on a free loopback port and stop it again (shared by
the interop scripts). Waits are bounded; nothing sleeps a fixed time."""
import re
import signal
import subprocess
import sys


class Emulator:
    def __init__(self, hilbridge, profile="cia402", extra=()):
        self.proc = subprocess.Popen(
            [hilbridge, "emulate", "modbus-drive", "--listen", "127.0.0.1:0", "--profile", profile, *extra],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.proc.stdout.readline()  # the emulator prints its address first, then serves
        m = re.search(r"listening on 127\.0\.0\.1:(\d+)", line)
        if not m:
            self.proc.kill()
            out, err = self.proc.communicate(timeout=5)
            sys.exit(f"emulator did not start: {line!r} {out!r} {err!r}")
        self.port = int(m.group(1))

    def stop(self):
        """SIGTERM; returns (exit code, remaining stdout, stderr)."""
        self.proc.send_signal(signal.SIGTERM)
        out, err = self.proc.communicate(timeout=10)
        return self.proc.returncode, out, err

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.communicate(timeout=10)


class Checks:
    def __init__(self):
        self.failed = 0
        self.passed = 0

    def check(self, cond, what):
        if cond:
            self.passed += 1
        else:
            self.failed += 1
            print(f"FAIL: {what}", flush=True)

    def exit(self):
        print(f"{self.passed} checks passed, {self.failed} failed")
        sys.exit(1 if self.failed or not self.passed else 0)
