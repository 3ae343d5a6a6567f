#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Independent CANopen master for tests/canopen/test_interop_python.cpp: Debian's python3-can
# (socketcand interface) talks NMT, SDO and PDO to hilbridge's simulated CiA 402 node through
# hilbridge's socketcand hub. Every request is one frame, every answer is checked byte for byte
# against CiA 301 / CiA 402 (written here from the specification, not from our code).
# Usage: canopen_peer.py HOST PORT CHANNEL NODE
import sys

import can

host, port, channel, node = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
bus = can.Bus(interface="socketcand", host=host, port=port, channel=channel)
print("READY", flush=True)


def fail(msg):
    print("FAIL " + msg, flush=True)
    bus.shutdown()
    sys.exit(1)


def expect(cob_id, data_hex, what):
    """Wait for a frame on cob_id; its data must be data_hex."""
    want = bytes.fromhex(data_hex)
    for _ in range(200):
        msg = bus.recv(timeout=5)
        if msg is None:
            fail(f"{what}: no frame on 0x{cob_id:03X}")
        if msg.arbitration_id != cob_id:
            continue
        got = bytes(msg.data)
        if got != want:
            fail(f"{what}: 0x{cob_id:03X} got {got.hex().upper()} want {want.hex().upper()}")
        print(f"OK {what}: {cob_id:03X}#{got.hex().upper()}", flush=True)
        return got
    fail(f"{what}: too many unrelated frames")


def send(cob_id, data_hex):
    bus.send(can.Message(arbitration_id=cob_id, data=bytes.fromhex(data_hex), is_extended_id=False))


sdo_rx, sdo_tx = 0x600 + node, 0x580 + node
n = f"{node:02X}"
try:
    # NMT reset communication -> boot-up message 0x700+id with state 0x00.
    send(0x000, "82" + n)
    expect(0x700 + node, "00", "boot-up after NMT reset communication")
    # Expedited upload 0x1018:01 vendor-ID 0x00000A11 (ccs 2 -> scs 2, e=1 s=1 n=0: 0x43).
    send(sdo_rx, "4018100100000000")
    expect(sdo_tx, "4318100111" + "0A0000", "expedited upload 0x1018:1")
    # Expedited download 0x6060 = 8 (one byte: 0x2F) -> 0x60.
    send(sdo_rx, "2F60600008000000")
    expect(sdo_tx, "6060600000000000", "expedited download 0x6060")
    # Segmented upload of the device name 0x1008 (33 bytes), toggling 0x60 / 0x70.
    name = b"hilbridge simulated CiA 402 drive"
    send(sdo_rx, "4008100000000000")
    expect(sdo_tx, "41081000" + len(name).to_bytes(4, "little").hex(), "segmented upload initiate 0x1008")
    got = b""
    toggle = 0
    while True:
        send(sdo_rx, f"{0x60 | (toggle << 4):02X}00000000000000")
        msg = bus.recv(timeout=5)
        while msg is not None and msg.arbitration_id != sdo_tx:
            msg = bus.recv(timeout=5)
        if msg is None:
            fail("segmented upload: no segment")
        b0 = msg.data[0]
        if (b0 >> 5) != 0 or ((b0 >> 4) & 1) != toggle:
            fail(f"segmented upload: bad segment header {b0:02X}")
        size = 7 - ((b0 >> 1) & 7)
        got += bytes(msg.data[1:1 + size])
        if b0 & 1:
            break
        toggle ^= 1
    if got != name:
        fail(f"segmented upload: got {got!r}")
    print("OK segmented upload 0x1008: " + got.decode(), flush=True)
    # Aborts: sub-index does not exist 0x06090011, write to a read-only object 0x06010002.
    send(sdo_rx, "4018100900000000")
    expect(sdo_tx, "8018100911000906", "abort sub-index does not exist")
    send(sdo_rx, "2300100001000000")
    expect(sdo_tx, "8000100002000106", "abort write to read-only object")
    # CiA 301 remapping of TPDO1 to the statusword alone, synchronous every SYNC; TPDO2 off.
    tpdo1 = (0x180 + node).to_bytes(4, "little")
    steps = [
        ("23001801" + (0x80000000 | (0x180 + node)).to_bytes(4, "little").hex(), "60001801", "TPDO1 disable"),
        ("2F001A0000000000", "60001A00", "TPDO1 mapping count 0"),
        ("23001A0110004160", "60001A01", "TPDO1 entry 0x60410010"),
        ("2F001A0001000000", "60001A00", "TPDO1 mapping count 1"),
        ("2F00180201000000", "60001802", "TPDO1 transmission type 1"),
        ("23001801" + tpdo1.hex(), "60001801", "TPDO1 enable"),
        ("23011801" + (0x80000000 | (0x280 + node)).to_bytes(4, "little").hex(), "60011801", "TPDO2 disable"),
    ]
    for req, rsp, what in steps:
        send(sdo_rx, req)
        expect(sdo_tx, rsp + "00000000", what)
    # NMT start, SYNC -> TPDO1 with the statusword: switch on disabled + remote = 0x0240.
    send(0x000, "01" + n)
    send(0x080, "")
    expect(0x180 + node, "4002", "TPDO1 after SYNC (switch on disabled)")
    # RPDO1 (controlword + modes of operation): shutdown 0x0006 -> ready to switch on 0x0221.
    send(0x200 + node, "060008")
    send(0x080, "")
    got = expect(0x180 + node, "2102", "TPDO1 after shutdown (ready to switch on)")
    print("DONE", flush=True)
finally:
    bus.shutdown()
