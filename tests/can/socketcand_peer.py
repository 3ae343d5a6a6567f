#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Independent peer for tests/can/test_socketcand_python.cpp: Debian's python3-can (socketcand
# interface) against `hilbridge`'s socketcand hub. Echo protocol:
#   for each of COUNT received frames: reply with id+1 and the data reversed;
#   then send 7FF#5059 ("PY") and exit 0. Any timeout exits non-zero with a message.
# Usage: socketcand_peer.py HOST PORT CHANNEL COUNT
import sys

import can

host, port, channel, count = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
bus = can.Bus(interface="socketcand", host=host, port=port, channel=channel)
print("READY", flush=True)
try:
    for i in range(count):
        msg = bus.recv(timeout=10)
        if msg is None:
            print(f"TIMEOUT waiting for frame {i}", flush=True)
            sys.exit(2)
        print(f"RX {msg.arbitration_id:X}#{bytes(msg.data).hex().upper()}", flush=True)
        reply_id = msg.arbitration_id + 1
        reply = can.Message(arbitration_id=reply_id, data=bytes(reversed(msg.data)),
                            is_extended_id=reply_id > 0x7FF)
        bus.send(reply)
    bus.send(can.Message(arbitration_id=0x7FF, data=b"PY", is_extended_id=False))
    print("DONE", flush=True)
finally:
    bus.shutdown()
