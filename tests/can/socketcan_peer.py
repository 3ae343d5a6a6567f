#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Independent peer for tests/can/test_socketcan_kernel.cpp: Debian's python3-can with its
# `socketcan` interface on a vcan interface. For each of COUNT received frames it replies with
# id+1 and the data reversed (remote frames are answered with a 1-byte data frame 0x55), then
# sends 7FF#5059 and exits 0.  Usage: socketcan_peer.py CHANNEL COUNT
import sys

import can

channel, count = sys.argv[1], int(sys.argv[2])
bus = can.Bus(interface="socketcan", channel=channel)
print("READY", flush=True)
try:
    for i in range(count):
        msg = bus.recv(timeout=60)
        if msg is None:
            print(f"TIMEOUT waiting for frame {i}", flush=True)
            sys.exit(2)
        kind = "R" if msg.is_remote_frame else ""
        print(f"RX {msg.arbitration_id:X}#{kind}{bytes(msg.data).hex().upper()} ext={int(msg.is_extended_id)}", flush=True)
        data = b"\x55" if msg.is_remote_frame else bytes(reversed(msg.data))
        bus.send(can.Message(arbitration_id=msg.arbitration_id + 1, data=data, is_extended_id=msg.is_extended_id))
    bus.send(can.Message(arbitration_id=0x7FF, data=b"PY", is_extended_id=False))
    print("DONE", flush=True)
finally:
    bus.shutdown()
