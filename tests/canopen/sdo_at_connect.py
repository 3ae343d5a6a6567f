#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Independent peer for tests/canopen/test_interop_python.cpp: Debian's python3-can (socketcand
# interface) connects to hilbridge's socketcand hub, sends an SDO upload request of 0x1000 in the
# same millisecond as connect() returns, and must get the node's answer. Repeated ROUNDS times,
# each with a fresh connection, on a bus that carries a SYNC every millisecond. A round whose
# request left 1 ms or more after connect() (this process was descheduled: a busy machine) did not
# test the race; it still must be answered, and is repeated (at most 4 x ROUNDS connections).
# The last line says how many connections were made ("CONNECTIONS n").
# Usage: sdo_at_connect.py HOST PORT CHANNEL NODE ROUNDS
import sys
import time

import can

host, port, channel, node, rounds = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
request = can.Message(arbitration_id=0x600 + node, data=bytes.fromhex("4000100000000000"), is_extended_id=False)
worst_ms = 0.0
racing = late = connections = 0
while racing < rounds:
    if connections >= 4 * rounds:
        print(f"FAIL only {racing} of {connections} requests left within 1 ms of connect(): the machine is too busy",
              flush=True)
        sys.exit(1)
    i = connections
    connections += 1
    bus = can.Bus(interface="socketcand", host=host, port=port, channel=channel)
    connected = time.monotonic()
    bus.send(request)
    sent_ms = (time.monotonic() - connected) * 1000.0
    answer = None
    deadline = time.monotonic() + 2.0
    while time.monotonic() < deadline:
        msg = bus.recv(timeout=0.5)
        if msg is not None and msg.arbitration_id == 0x580 + node:
            answer = bytes(msg.data)
            break
    bus.shutdown()
    if answer is None:
        print(f"FAIL round {i}: no SDO answer on 0x{0x580 + node:03X} within 2 s", flush=True)
        sys.exit(1)
    # Expedited upload response, 4 bytes (0x43), index 0x1000 sub 0.
    if answer[:4] != bytes.fromhex("43001000"):
        print(f"FAIL round {i}: answer {answer.hex().upper()}", flush=True)
        sys.exit(1)
    if sent_ms >= 1.0:
        late += 1
        print(f"LATE round {i}: the request left {sent_ms:.3f} ms after connect() (answered; repeated)", flush=True)
        continue
    racing += 1
    worst_ms = max(worst_ms, sent_ms)
    print(f"OK round {i}: sent {sent_ms:.3f} ms after connect, answer {answer.hex().upper()}", flush=True)
print(f"DONE {rounds} rounds, worst send delay {worst_ms:.3f} ms, {late} late rounds repeated", flush=True)
print(f"CONNECTIONS {connections}", flush=True)
