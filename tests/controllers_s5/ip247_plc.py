# SPDX-License-Identifier: MIT
# The IP247 PLC helpers of the Python PLC tests (plc_ip247.py, plc_ip247_rack.py): the MD DB and VP DB
# images, the axis status words of DX n, waiting for the end of a job, a data job through DX 4.
import time

from s5_plc_link import dd, s32  # 3964R + RK512, the PLC side (python3-serial)


def md_db(db):
    """MD DB (manual §6.3.8.1): 10 µm/pulse, fmax 5 kHz, NO limit switches, 70 words."""
    w = [70, 0x0044, 0x4200 | db, (0 << 8) | 1, (1 << 8) | 0]
    w += dd(5000) + dd(200) + dd(50000)          # fmax, fss, a (mHz/ms)
    w += [30, 0x40, 4, 200] + dd(2000)           # pulse, polarity, patterns, pulses/rev, gear
    w += dd(3000) * 4                            # jog 1, jog 2, incremental, reference speed
    w += [1, 0x20] + dd(0) + dd(-400000) + dd(500000)  # sync no, ref backward, ref coord, SW limits
    w += [0] + dd(0) + dd(0) + dd(0) * 4 + [0, 0]      # NO switches, tool, backlash, zero offsets, linear, binary
    w += [0] * (70 - len(w))
    return w


def vp_db(db, text):
    raw = text.encode("ascii")
    if len(raw) % 2:
        raw += b"\0"
    words = [(raw[i] << 8) | raw[i + 1] for i in range(0, len(raw), 2)]
    return [5 + len(words), 0x0044, 0x4200 | db, 0, 0] + words


def status(link):
    err, w = link.fetch(1, 0, 14, typ="X")
    assert err == 0, err
    return {"actual": s32(w[5], w[6]), "remaining": s32(w[9], w[10]), "ba": w[11] >> 8, "m": w[11] & 0xFF,
            "attr": w[12] >> 8, "error": w[12] & 0xFF}


def wait_finished(link, timeout=30):
    deadline = time.time() + timeout
    samples = []
    while time.time() < deadline:
        s = status(link)
        samples.append(s)
        if s["attr"] & 0x80:
            return s, samples
        time.sleep(0.05)
    raise TimeoutError("axis did not finish")


def data_job(link, ba, q_db=0, q_start=0, z_db=0, z_start=0, ssnr=0):
    """A data job through the job block DX 4 (FB165's 15 words): parameters, then DW0 = BA; the
    module runs it and writes DW0 = 0. Returns the block (DW6 flags, DW7 MB250/MB251, DW9 words)."""
    assert link.send(4, 1, [q_db, q_start, z_db, z_start, ssnr], typ="X") == 0
    assert link.send(4, 0, [ba], typ="X") == 0
    err, w = link.fetch(4, 0, 15, typ="X")
    assert err == 0, err
    return w
