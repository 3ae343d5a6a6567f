# SPDX-License-Identifier: MIT
"""An independent Modbus/TCP drive for our ModbusDrive to talk to: pymodbus 3.0's asyncio server
(its own MBAP framing) with a small CiA 402 device written here in Python, on the register layout
of profiles/modbus/cia402.yaml (holding registers 0..31; control word 0, mode 1, target position
2-3, target velocity 4-5, status word 10, actual position 11-12, actual velocity 13-14, error
code 15). The actual position follows the target at once while operation is enabled.
Prints "port N" once it accepts connections.
Usage: /usr/bin/python3 pymodbus_cia402_server.py [--port N]"""
import argparse
import asyncio
import sys

import pymodbus_compat  # noqa: F401  (before pymodbus)
from pymodbus.datastore import ModbusSequentialDataBlock, ModbusServerContext, ModbusSlaveContext
from pymodbus.server import StartAsyncTcpServer

SOD, RTSO, SO, OE, QSA = 0x40, 0x21, 0x23, 0x27, 0x07


class Cia402Block(ModbusSequentialDataBlock):
    def __init__(self):
        super().__init__(0, [0] * 32)
        self.state = SOD
        super().setValues(10, [0x0200 | SOD])

    def next_state(self, cw):
        s = self.state
        if s == SOD:
            return RTSO if cw & 0x87 == 0x06 else s
        if not cw & 0x02:
            return SOD  # disable voltage
        if cw & 0x06 == 0x02:
            return QSA if s == OE else SOD  # quick stop
        if s == QSA:
            return SOD
        if cw & 0x87 == 0x06:
            return RTSO
        if cw & 0x8F == 0x07:
            return SO if s in (RTSO, SO, OE) else s
        if cw & 0x8F == 0x0F:
            return OE if s in (RTSO, SO, OE) else s
        return s

    def setValues(self, address, values):  # noqa: N802 (pymodbus API)
        super().setValues(address, values)
        regs = self.getValues(0, 16)
        if address <= 0 < address + len(values):
            self.state = self.next_state(regs[0])
        if self.state == OE:  # an ideal drive: actual = target
            super().setValues(11, [regs[2], regs[3], regs[4], regs[5]])
        super().setValues(10, [0x0200 | self.state | (0x10 if self.state in (SO, OE, QSA) else 0)])


async def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--port", type=int, default=0)
    args = ap.parse_args()
    slave = ModbusSlaveContext(hr=Cia402Block(), ir=ModbusSequentialDataBlock(0, [0] * 8), zero_mode=True)
    context = ModbusServerContext(slaves=slave, single=True)
    server = await StartAsyncTcpServer(context=context, address=("127.0.0.1", args.port), defer_start=True,
                                       allow_reuse_address=True)
    task = asyncio.create_task(server.serve_forever())
    await server.serving
    print(f"port {server.server.sockets[0].getsockname()[1]}", flush=True)
    await task


if __name__ == "__main__":
    try:
        asyncio.run(main())
    except KeyboardInterrupt:
        sys.exit(0)
