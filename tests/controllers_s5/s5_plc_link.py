# SPDX-License-Identifier: MIT
# The PLC side of 3964R (with BCC) and RK512 SEND/FETCH for the Python PLC tests, written from the
# notes (shared/notes), no hilbridge code: python3-serial on the emulator's pty.
import struct
import time

import serial  # python3-serial

STX, ETX, DLE, NAK = 0x02, 0x03, 0x10, 0x15


class Link:
    """3964R (with BCC) plus RK512 SEND/FETCH of data blocks, the PLC side."""

    def __init__(self, path, baud=9600):
        self.port = serial.Serial(path, baud, bytesize=8, parity="N", stopbits=1, timeout=2)

    def read1(self):
        c = self.port.read(1)
        if not c:
            raise TimeoutError("no character within 2 s")
        return c[0]

    def send_block(self, payload: bytes):
        body = bytearray()
        for b in payload:
            body.append(b)
            if b == DLE:
                body.append(DLE)
        body += bytes([DLE, ETX])
        bcc = 0
        for b in body:
            bcc ^= b
        for _ in range(6):
            self.port.write(bytes([STX]))
            if self.read1() != DLE:
                time.sleep(0.05)
                continue
            self.port.write(bytes(body) + bytes([bcc]))
            if self.read1() == DLE:
                return
        raise RuntimeError("3964R: block not acknowledged")

    def recv_block(self) -> bytes:
        deadline = time.time() + 5
        while self.read1() != STX:
            if time.time() > deadline:
                raise TimeoutError("no STX")
        self.port.write(bytes([DLE]))
        data, bcc = bytearray(), 0
        while True:
            c = self.read1()
            bcc ^= c
            if c == DLE:
                d = self.read1()
                bcc ^= d
                if d == ETX:
                    break
                data.append(d)  # doubled DLE
            else:
                data.append(c)
        if self.read1() != bcc:
            self.port.write(bytes([NAK]))
            raise RuntimeError("3964R: BCC error")
        self.port.write(bytes([DLE]))
        return bytes(data)

    def reaction(self, expect_bytes=0):
        t = self.recv_block()
        assert t[0] == 0 and t[1] == 0 and t[2] == 0, t.hex()
        err, data = t[3], bytearray(t[4:])
        while err == 0 and len(data) < expect_bytes:
            c = self.recv_block()
            assert c[0] == 0xFF
            data += c[4:]
        return err, bytes(data)

    def send(self, db, dw, words, typ="D"):
        """RK512 SEND of `words` to DB `db` from DW `dw`: the reaction's error byte (0 = ok)."""
        data = b"".join(struct.pack(">H", w & 0xFFFF) for w in words)
        cmd = ord("A") if typ == "D" else ord("O")
        first = bytes([0, 0, cmd, ord(typ), db, dw, len(words) >> 8, len(words) & 0xFF, 0xFF, 0xFF])
        self.send_block(first + data[:128])
        pos = 128
        while pos < len(data):
            self.send_block(bytes([0xFF, 0, cmd, ord(typ)]) + data[pos:pos + 128])
            pos += 128
        return self.reaction()[0]

    def fetch(self, db, dw, n, typ="D"):
        """RK512 FETCH of `n` words of DB `db` from DW `dw`: (error byte, words)."""
        self.send_block(bytes([0, 0, ord("E"), ord(typ), db, dw, n >> 8, n & 0xFF, 0xFF, 0xFF]))
        err, data = self.reaction(2 * n)
        return err, [struct.unpack(">H", data[i:i + 2])[0] for i in range(0, len(data), 2)]


def dd(v):
    """A 32-bit value as two S5 words (high word first)."""
    v &= 0xFFFFFFFF
    return [v >> 16, v & 0xFFFF]


def s32(hi, lo):
    v = (hi << 16) | lo
    return v - (1 << 32) if v & 0x80000000 else v
