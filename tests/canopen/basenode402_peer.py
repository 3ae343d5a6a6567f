#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Independent CiA 402 master for tests/canopen/test_interop_python.cpp, written with Debian's
# python3-can (socketcand interface) only. It scripts the SDO/NMT/PDO sequence python-canopen's
# BaseNode402 runs (setup_402_state_machine: pre-operational, read the PDO configuration by SDO;
# NMT start and wait for the TPDOs; state changes through the controlword, checked on the
# statusword; op_mode by 0x6060 / 0x6061; a profile-position move with the set-point handshake)
# against `hilbridge emulate cia402 --eds FILE` behind `hilbridge`'s socketcand hub. Everything
# is checked against CiA 301 / CiA 402 as written here, not against our code.
# Usage: basenode402_peer.py HOST PORT CHANNEL NODE
import struct
import sys
import time

import can

host, port, channel, node = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
bus = can.Bus(interface="socketcand", host=host, port=port, channel=channel)
print("READY", flush=True)
SDO_RX, SDO_TX = 0x600 + node, 0x580 + node


def fail(msg):
    print("FAIL " + msg, flush=True)
    bus.shutdown()
    sys.exit(1)


def send(cob_id, data):
    bus.send(can.Message(arbitration_id=cob_id, data=bytes(data), is_extended_id=False))


def sdo(request, what):
    """One expedited SDO exchange; retried (python-can 4.1 may lose a frame of a burst)."""
    for _ in range(3):
        send(SDO_RX, request)
        deadline = time.monotonic() + 0.5
        while time.monotonic() < deadline:
            msg = bus.recv(timeout=0.1)
            if msg is not None and msg.arbitration_id == SDO_TX and bytes(msg.data[1:4]) == bytes(request[1:4]):
                if msg.data[0] == 0x80:
                    fail(f"{what}: abort 0x{struct.unpack('<I', bytes(msg.data[4:8]))[0]:08X}")
                return bytes(msg.data)
    fail(f"{what}: no SDO answer")


def upload(index, sub, what):
    rsp = sdo([0x40, index & 0xFF, index >> 8, sub, 0, 0, 0, 0], what)
    if (rsp[0] & 0xE0) != 0x40 or not rsp[0] & 0x02:
        fail(f"{what}: not an expedited upload answer {rsp.hex()}")
    size = 4 - ((rsp[0] >> 2) & 3) if rsp[0] & 0x01 else 4
    return int.from_bytes(rsp[4:4 + size], "little")


def download(index, sub, value, size, what):
    cmd = {1: 0x2F, 2: 0x2B, 4: 0x23}[size]
    data = list(int(value & ((1 << (8 * size)) - 1)).to_bytes(size, "little")) + [0] * (4 - size)
    rsp = sdo([cmd, index & 0xFF, index >> 8, sub] + data, what)
    if rsp[0] != 0x60:
        fail(f"{what}: download answered {rsp.hex()}")


def frames_for(seconds):
    out = []
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        msg = bus.recv(timeout=0.05)
        if msg is not None:
            out.append(msg)
    return out


try:
    # setup_402_state_machine(): pre-operational, then read the PDO configuration (pdo.read()).
    send(0x000, [0x80, node])
    time.sleep(0.05)
    tpdos = {}
    for n in range(4):
        cob = upload(0x1800 + n, 1, f"TPDO{n + 1} COB-ID")
        count = upload(0x1A00 + n, 0, f"TPDO{n + 1} mapping count")
        entries = [upload(0x1A00 + n, k, f"TPDO{n + 1} entry {k}") for k in range(1, count + 1)]
        if not cob & 0x80000000 and entries:
            tpdos[cob & 0x7FF] = entries
    print("OK TPDOs " + ", ".join(f"{c:03X}:" + "+".join(f"{e:08X}" for e in m) for c, m in tpdos.items()),
          flush=True)
    sw_pdo = [c for c, m in tpdos.items() if m[0] >> 16 == 0x6041]
    if not sw_pdo:
        fail("no TPDO carries the statusword")
    sw_cob = sw_pdo[0]

    def statusword_from(msgs):
        words = [m.data[0] | (m.data[1] << 8) for m in msgs if m.arbitration_id == sw_cob and len(m.data) >= 2]
        return words

    # NMT start / stop / start: the node sends its TPDOs after every start.
    for round_ in ("first start", "stop", "second start"):
        send(0x000, [0x02 if round_ == "stop" else 0x01, node])
        words = statusword_from(frames_for(0.3))
        if round_ == "stop":
            if words:
                fail("TPDOs while stopped")
            print("OK no TPDOs while stopped", flush=True)
        else:
            if not words:
                fail(f"no statusword TPDO after the {round_}")
            print(f"OK statusword TPDO after the {round_}: 0x{words[-1]:04X}", flush=True)
    if (words[-1] & 0x4F) != 0x40:
        fail(f"expected SWITCH ON DISABLED, statusword 0x{words[-1]:04X}")

    # BaseNode402.state = 'OPERATION ENABLED': shutdown, switch on, enable operation; each state
    # checked on the statusword (mask/value from CiA 402 table 30).
    def controlword(value, what):
        download(0x6040, 0, value, 2, what)

    def wait_state(mask, value, what):
        deadline = time.monotonic() + 2.0
        while time.monotonic() < deadline:
            sw = upload(0x6041, 0, what)
            if (sw & mask) == value:
                print(f"OK {what}: statusword 0x{sw:04X}", flush=True)
                return sw
            time.sleep(0.01)
        fail(f"{what}: statusword 0x{sw:04X}")

    controlword(0x06, "shutdown")
    wait_state(0x6F, 0x21, "READY TO SWITCH ON")
    controlword(0x07, "switch on")
    wait_state(0x6F, 0x23, "SWITCHED ON")
    controlword(0x0F, "enable operation")
    wait_state(0x6F, 0x27, "OPERATION ENABLED")

    # op_mode = 'PROFILED POSITION': 0x6060 = 1, confirmed by 0x6061.
    download(0x6060, 0, 1, 1, "modes of operation PP")
    deadline = time.monotonic() + 1.0
    while upload(0x6061, 0, "modes of operation display") != 1:
        if time.monotonic() > deadline:
            fail("0x6061 never showed PP")
    print("OK modes of operation display = 1 (PP)", flush=True)
    start = upload(0x6064, 0, "position actual")
    if start >= 1 << 31:
        start -= 1 << 32
    target = start + 5000
    download(0x6081, 0, 10000, 4, "profile velocity")
    download(0x6083, 0, 50000, 4, "profile acceleration")
    download(0x6084, 0, 50000, 4, "profile deceleration")
    download(0x607A, 0, target, 4, "target position")
    controlword(0x1F, "new set-point (bit 4)")
    wait_state(0x1000, 0x1000, "set-point acknowledge (bit 12)")
    controlword(0x0F, "bit 4 low")
    deadline = time.monotonic() + 5.0
    while True:
        sw = upload(0x6041, 0, "statusword")
        pos = upload(0x6064, 0, "position actual")
        if pos >= 1 << 31:
            pos -= 1 << 32
        if (sw & 0x0400) and abs(pos - target) <= 20:
            break
        if time.monotonic() > deadline:
            fail(f"PP move: position {pos}, target {target}, statusword 0x{sw:04X}")
        time.sleep(0.02)
    print(f"OK PP move to {target}: position {pos}, target reached", flush=True)
    print("DONE", flush=True)
finally:
    bus.shutdown()
