# SPDX-License-Identifier: MIT
"""pymodbus 3.0 (independent implementation, MBAP-length framing) as a client of our simulated
drive server: FC 3/4/6/16/22/23, the CiA 402 enable sequence, exceptions 01/02, several clients
at once, garbage and half frames from other sockets.
Usage: /usr/bin/python3 interop_pymodbus_client.py HILBRIDGE"""
import socket
import sys
import threading
import time

import pymodbus_compat  # noqa: F401  (before pymodbus)
from pymodbus.client import ModbusTcpClient

from emulator import Checks, Emulator


def wait_for(pred, timeout_s=3.0):
    """Poll `pred` (a Modbus read) until true or the deadline; each poll is a round trip."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if pred():
            return True
    return False


def s32(hi, lo):
    v = (hi << 16) | lo
    return v - (1 << 32) if v & 0x80000000 else v


def main():
    hilbridge = sys.argv[1]
    c = Checks()
    with Emulator(hilbridge, "cia402") as emu:
        cl = ModbusTcpClient("127.0.0.1", port=emu.port, timeout=2)
        c.check(cl.connect(), "connect")
        rr = cl.read_holding_registers(10, 6, slave=1)
        c.check(not rr.isError() and len(rr.registers) == 6, f"FC3 status block: {rr}")
        c.check(rr.registers[0] & 0x4F == 0x40, f"switch on disabled: 0x{rr.registers[0]:04x}")

        # CiA 402 enable sequence with FC 6.
        for cw, want in ((0x06, 0x21), (0x07, 0x23), (0x0F, 0x27)):
            wr = cl.write_register(0, cw, slave=1)
            c.check(not wr.isError(), f"FC6 control word 0x{cw:02x}")
            sw = cl.read_holding_registers(10, 1, slave=1).registers[0]
            c.check(sw & 0x6F == want, f"after 0x{cw:02x}: status 0x{sw:04x}, want 0x{want:02x}")

        # FC 16 target position (s32, high word first), the plant follows.
        target = -12345
        u = target & 0xFFFFFFFF
        wr = cl.write_registers(2, [u >> 16, u & 0xFFFF], slave=1)
        c.check(not wr.isError(), "FC16 target position")

        def at_target():
            r = cl.read_holding_registers(11, 2, slave=1)
            return not r.isError() and abs(s32(*r.registers) - target) <= 2
        c.check(wait_for(at_target), "actual position reaches the FC16 target")

        # FC 23: write control word, read the status block in one request.
        rw = cl.readwrite_registers(read_address=10, read_count=6, write_address=0, write_registers=[0x0F], slave=1)
        c.check(not rw.isError() and len(rw.registers) == 6 and rw.registers[0] & 0x6F == 0x27, f"FC23: {rw}")
        # FC 22 mask write: clear bit 3 of the control word (enable operation -> switch on).
        mw = cl.mask_write_register(address=0, and_mask=0xFFF7, or_mask=0x0000, slave=1)
        c.check(not mw.isError(), f"FC22: {mw}")
        sw = cl.read_holding_registers(10, 1, slave=1).registers[0]
        c.check(sw & 0x6F == 0x23, f"FC22 took the drive to switched on: 0x{sw:04x}")

        # Exceptions.
        r = cl.write_register(10, 1, slave=1)
        c.check(r.isError() and getattr(r, "exception_code", None) == 2, f"write read-only status word -> 02: {r}")
        r = cl.read_holding_registers(6, 4, slave=1)
        c.check(r.isError() and getattr(r, "exception_code", None) == 2, f"read gap -> 02: {r}")
        r = cl.read_input_registers(0, 1, slave=1)
        c.check(r.isError() and getattr(r, "exception_code", None) == 2, f"FC4 without input registers -> 02: {r}")
        r = cl.read_coils(0, 1, slave=1)
        c.check(r.isError() and getattr(r, "exception_code", None) == 1, f"FC1 -> 01: {r}")

        # Garbage and half frames on other connections; pymodbus keeps working.
        g = socket.create_connection(("127.0.0.1", emu.port), timeout=2)
        g.sendall(b"GET / HTTP/1.0\r\n\r\n")
        c.check(g.recv(16) == b"", "HTTP garbage: server closes that connection")
        g.close()
        h = socket.create_connection(("127.0.0.1", emu.port), timeout=2)
        h.sendall(bytes([0, 1, 0, 0, 0, 6, 1, 3]))
        h.close()
        rr = cl.read_holding_registers(10, 1, slave=1)
        c.check(not rr.isError(), "still served after garbage")

        # Several clients at once.
        errors = []

        def worker():
            k = ModbusTcpClient("127.0.0.1", port=emu.port, timeout=2)
            if not k.connect():
                errors.append("connect")
                return
            for _ in range(100):
                x = k.read_holding_registers(10, 6, slave=1)
                if x.isError() or len(x.registers) != 6:
                    errors.append(str(x))
            k.close()
        threads = [threading.Thread(target=worker) for _ in range(6)]
        for t in threads:
            t.start()
        for t in threads:
            t.join(timeout=30)
        c.check(not errors, f"6 concurrent pymodbus clients: {errors[:3]}")
        cl.close()
        code, out, err = emu.stop()
        c.check(code == 0, f"emulator exits 0 on SIGTERM: {code} {err}")
        c.check("malformed" in out and "1 malformed" in out, f"emulator stats: {out.strip()}")

    with Emulator(hilbridge, "vendor_simple") as emu:
        cl = ModbusTcpClient("127.0.0.1", port=emu.port, timeout=2)
        c.check(cl.connect(), "connect vendor")
        rr = cl.read_input_registers(0, 5, slave=1)
        c.check(not rr.isError() and rr.registers[0] & 0x1 == 1, f"FC4 vendor status ready: {rr}")
        wr = cl.write_registers(102, [0x5678, 0x0001], slave=1)  # low word first: 0x00015678
        c.check(not wr.isError(), "FC16 vendor target")
        cl.write_register(100, 1, slave=1)  # enable
        target = 0x00015678

        def at_vendor_target():
            r = cl.read_input_registers(1, 2, slave=1)
            return not r.isError() and abs(((r.registers[1] << 16) | r.registers[0]) - target) <= 2
        c.check(wait_for(at_vendor_target), "vendor position (low word first) reaches the target")
        r = cl.readwrite_registers(read_address=0, read_count=1, write_address=100, write_registers=[1], slave=1)
        c.check(r.isError() and getattr(r, "exception_code", None) == 2, f"FC23 read of absent holding reg -> 02: {r}")
        cl.close()
    c.exit()


if __name__ == "__main__":
    main()
