# SPDX-License-Identifier: MIT
# `hilbridge emulate clm14 --pty` as a child process, for the Python tests beside this file: it
# prints its pty path first, then answers one control command per line on stdin.
import subprocess


class Emulator:
    def __init__(self, hilbridge, *args):
        self.p = subprocess.Popen([hilbridge, "emulate", "clm14", "--pty", *args], stdin=subprocess.PIPE,
                                  stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        self.path = self.p.stdout.readline().strip()
        assert self.path.startswith("/dev/pts/"), f"emulator printed {self.path!r}"

    def command(self, line: str) -> str:
        self.p.stdin.write(line + "\n")
        self.p.stdin.flush()
        return self.p.stdout.readline().strip()

    def close(self):
        self.p.stdin.write("quit\n")
        self.p.stdin.flush()
        self.p.wait(timeout=10)
