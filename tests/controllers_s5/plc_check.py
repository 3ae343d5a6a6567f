# SPDX-License-Identifier: MIT
# The verdicts and the emulator's end for the Python PLC tests (plc_ip247*.py, plc_wf72*.py): check()
# prints each verdict and keeps the failed ones, finish() lists them and exits 1, stop() ends an
# emulator started with a console on stdin ("quit", else kill).
import sys

failures = []


def check(name, ok, detail=""):
    if ok:
        print(f"ok   {name}")
    else:
        failures.append(f"{name}: {detail}")
        print(f"FAIL {name}: {detail}")


def finish():
    if failures:
        print("\n".join(failures))
        sys.exit(1)


def stop(p):
    try:
        p.stdin.write("quit\n")
        p.stdin.flush()
        p.wait(timeout=10)
    except Exception:
        p.kill()
