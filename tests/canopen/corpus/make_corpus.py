#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Writes the EDS/DCF regression corpus of tests/canopen/test_eds_corpus.cpp. Each file reproduces
# one variation seen in real vendor files (none is copied from a vendor). The files are committed;
# run this script only to change them (python3 make_corpus.py in this folder).
import os

HERE = os.path.dirname(os.path.abspath(__file__))

U8, U16, U32, I8, I16, I32, I64, R32, VS, DOM = 0x5, 0x6, 0x7, 0x2, 0x3, 0x4, 0x15, 0x8, 0x9, 0xF


def var(name, dt, acc, default=None, pdo=0, low=None, high=None, pv=None):
    d = {"ParameterName": name, "ObjectType": "0x7", "DataType": f"0x{dt:04X}", "AccessType": acc}
    if default is not None:
        d["DefaultValue"] = default
    if pv is not None:
        d["ParameterValue"] = pv
    if low is not None:
        d["LowLimit"] = low
    if high is not None:
        d["HighLimit"] = high
    d["PDOMapping"] = str(pdo)
    return d


class Eds:
    def __init__(self, file, vendor, product, vendor_no, product_no, revision, granularity=8, rx=4, tx=4):
        self.file = file
        self.info = dict(VendorName=vendor, VendorNumber=f"0x{vendor_no:08X}", ProductName=product,
                         ProductNumber=f"0x{product_no:08X}", RevisionNumber=f"0x{revision:08X}",
                         OrderCode=product.replace(" ", "-"), BaudRate_250="1", BaudRate_500="1",
                         BaudRate_1000="1", SimpleBootUpSlave="1", Granularity=str(granularity),
                         NrOfRXPDO=str(rx), NrOfTXPDO=str(tx), LSS_Supported="0")
        self.objects = {}  # index -> (header dict, [sub dicts] or None, extra sections)
        self.comment = ""
        self.commissioning = None

    def add(self, index, d):
        self.objects[index] = (d, None, {})

    def record(self, index, name, subs, compact=None, obj_type="0x9"):
        self.objects[index] = ({"ParameterName": name, "ObjectType": obj_type, "SubNumber": str(sum(1 for s in subs if s is not None))}, subs, {})

    def compact(self, index, name, dt, acc, count, names=None, values=None, default="0"):
        d = {"ParameterName": name, "ObjectType": "0x8", "DataType": f"0x{dt:04X}", "AccessType": acc,
             "DefaultValue": default, "PDOMapping": "0", "CompactSubObj": str(count)}
        extra = {}
        if names:
            extra[f"{index:04X}Name"] = {"NrOfEntries": str(len(names)), **{str(k): v for k, v in names.items()}}
        if values:
            extra[f"{index:04X}Value"] = {"NrOfEntries": str(len(values)), **{str(k): v for k, v in values.items()}}
        self.objects[index] = (d, None, extra)

    def text(self):
        out = []
        if self.comment:
            out += ["; " + line for line in self.comment.splitlines()]
        out += ["[FileInfo]", f"FileName={self.file}", "FileVersion=1", "FileRevision=0", "EDSVersion=4.0",
                "Description=hilbridge regression corpus", "CreatedBy=hilbridge tests/canopen/corpus", ""]
        out += ["[DeviceInfo]"] + [f"{k}={v}" for k, v in self.info.items()] + [""]
        mandatory = [i for i in sorted(self.objects) if i in (0x1000, 0x1001, 0x1018)]
        optional = [i for i in sorted(self.objects) if i not in mandatory and not 0x2000 <= i <= 0x5FFF]
        manufacturer = [i for i in sorted(self.objects) if 0x2000 <= i <= 0x5FFF]
        for title, lst in (("MandatoryObjects", mandatory), ("OptionalObjects", optional),
                           ("ManufacturerObjects", manufacturer)):
            out += [f"[{title}]", f"SupportedObjects={len(lst)}"] + [f"{n + 1}=0x{i:04X}" for n, i in enumerate(lst)]
            out.append("")
        for index in sorted(self.objects):
            head, subs, extra = self.objects[index]
            out += [f"[{index:04X}]"] + [f"{k}={v}" for k, v in head.items()] + [""]
            if subs:
                for s, d in enumerate(subs):
                    if d is None:
                        continue
                    out += [f"[{index:04X}sub{s:X}]"] + [f"{k}={v}" for k, v in d.items()] + [""]
            for name, sec in extra.items():
                out += [f"[{name}]"] + [f"{k}={v}" for k, v in sec.items()] + [""]
        if self.commissioning:
            out += ["[DeviceComissioning]"] + [f"{k}={v}" for k, v in self.commissioning.items()] + [""]
        return "\n".join(out) + "\n"


def comm(eds, index, cob, tt="0xFF", rx=True, pv=None, acc="rw", inhibit=True):
    subs = [var("Highest sub-index supported", U8, "ro", "5" if rx else "6"),
            var("COB-ID", U32, acc, cob, pv=pv.get(1) if pv else None),
            var("Transmission type", U8, acc, tt, pv=pv.get(2) if pv else None)]
    subs.append(var("Inhibit time", U16, "rw", "0", pv=pv.get(3) if pv else None) if inhibit else None)
    subs.append(None)
    subs.append(var("Event timer", U16, "rw", "0", pv=pv.get(5) if pv else None))
    if not rx:
        subs.append(var("SYNC start value", U8, "rw", "0"))
    eds.record(index, ("Receive" if rx else "Transmit") + f" PDO {index & 0x1FF} parameter", subs)


def mapping(eds, index, entries, slots=8, acc="rw", pv=None):
    subs = [var("Number of mapped objects", U8, acc, str(len(entries)), pv=pv.get(0) if pv else None)]
    for s in range(1, slots + 1):
        e = entries[s - 1] if s <= len(entries) else "0x00000000"
        subs.append(var(f"Mapped object {s}", U32, acc, e, pv=pv.get(s) if pv else None))
    eds.record(index, f"PDO mapping {index:04X}", subs)


def base_301(eds, device_type="0x00020192", heartbeat=True, guarding=False, emcy=True):
    eds.add(0x1000, var("Device type", U32, "ro", device_type))
    eds.add(0x1001, var("Error register", U8, "ro", "0", pdo=1))
    eds.add(0x1008, var("Manufacturer device name", VS, "const", eds.info["ProductName"]))
    if emcy:
        eds.add(0x1014, var("COB-ID EMCY", U32, "rw", "$NODEID+0x80"))
    if guarding:
        eds.add(0x100C, var("Guard time", U16, "rw", "0"))
        eds.add(0x100D, var("Life time factor", U8, "rw", "0"))
    if heartbeat:
        eds.compact(0x1016, "Consumer heartbeat time", U32, "rw", 1)
        eds.add(0x1017, var("Producer heartbeat time", U16, "rw", "0"))
    eds.record(0x1018, "Identity object", [
        var("Number of entries", U8, "ro", "4"),
        var("Vendor-ID", U32, "ro", eds.info["VendorNumber"]),
        var("Product code", U32, "ro", eds.info["ProductNumber"]),
        var("Revision number", U32, "ro", eds.info["RevisionNumber"]),
        var("Serial number", U32, "ro", "0x00000001")])
    eds.record(0x1200, "Server SDO parameter", [
        var("Number of entries", U8, "ro", "2"),
        var("COB-ID client to server", U32, "ro", "$NODEID+0x600"),
        var("COB-ID server to client", U32, "ro", "$NODEID+0x580")])


def pdos(eds, rx=4, tx=4, slots=8, rx_maps=None, tx_maps=None, map_acc="rw", comm_acc="rw", cob_style=None):
    rx_maps = rx_maps or [[] for _ in range(rx)]
    tx_maps = tx_maps or [[] for _ in range(tx)]
    for n in range(rx):
        cob = cob_style(0x200 + 0x100 * n) if cob_style else f"$NODEID+0x{0x200 + 0x100 * n:X}"
        comm(eds, 0x1400 + n, cob, rx=True, acc=comm_acc)
        mapping(eds, 0x1600 + n, rx_maps[n], slots, map_acc)
    for n in range(tx):
        cob = cob_style(0x180 + 0x100 * n) if cob_style else f"$NODEID+0x{0x180 + 0x100 * n:X}"
        comm(eds, 0x1800 + n, cob, rx=False, acc=comm_acc)
        mapping(eds, 0x1A00 + n, tx_maps[n], slots, map_acc)


def drive(eds, modes, error_code=True, bits16=False, pdo=1, extra=True):
    pos = I16 if bits16 else I32
    upos = U16 if bits16 else U32
    if error_code:
        eds.add(0x603F, var("Error code", U16, "ro", "0", pdo=pdo))
    eds.add(0x6040, var("Controlword", U16, "rww", "0", pdo=pdo))
    eds.add(0x6041, var("Statusword", U16, "ro", "0", pdo=pdo))
    eds.add(0x605A, var("Quick stop option code", I16, "rw", "2"))
    eds.add(0x6060, var("Modes of operation", I8, "rww", "0", pdo=pdo))
    eds.add(0x6061, var("Modes of operation display", I8, "ro", "0", pdo=pdo))
    eds.add(0x6064, var("Position actual value", pos, "ro", "0", pdo=pdo))
    eds.add(0x6065, var("Following error window", upos, "rw", "20000"))
    eds.add(0x6066, var("Following error time out", U16, "rw", "10"))
    eds.add(0x6067, var("Position window", upos, "rw", "20"))
    eds.add(0x606C, var("Velocity actual value", pos, "ro", "0", pdo=pdo))
    eds.add(0x607A, var("Target position", pos, "rww", "0", pdo=pdo))
    eds.add(0x6081, var("Profile velocity", upos, "rww", "10000", pdo=pdo))
    eds.add(0x6083, var("Profile acceleration", upos, "rww", "20000", pdo=pdo))
    eds.add(0x6084, var("Profile deceleration", upos, "rww", "20000", pdo=pdo))
    eds.add(0x6085, var("Quick stop deceleration", upos, "rw", "50000"))
    eds.add(0x6098, var("Homing method", I8, "rw", "35"))
    if extra:
        eds.add(0x6077, var("Torque actual value", I16, "ro", "0", pdo=pdo))
        eds.add(0x60F4, var("Following error actual value", pos, "ro", "0", pdo=pdo))
        eds.add(0x60FD, var("Digital inputs", U32, "ro", "0", pdo=pdo))
    if modes & ((1 << 2) | (1 << 8)):
        eds.add(0x60FF, var("Target velocity", pos, "rww", "0", pdo=pdo))
    eds.add(0x6502, var("Supported drive modes", U32, "ro", f"0x{modes:08X}"))


ALL = (1 << 0) | (1 << 2) | (1 << 5) | (1 << 7) | (1 << 8)  # PP, PV, HM, CSP, CSV
files = {}

# 01: no 0x603F (the master must not map it, and says so).
e = Eds("v01_no_603f.eds", "Corpus Motion", "Servo without error code", 0x100, 0x101, 0x00010002)
base_301(e)
pdos(e, tx_maps=[["0x60410010", "0x60610008"], ["0x60640020"], [], []])
drive(e, ALL, error_code=False)
e.comment = "Vendor variation: no 0x603F error code object (fault codes only by EMCY)."
files[e.file] = e.text()

# 02: fixed PDO mapping (Granularity 0, read-only mapping objects).
e = Eds("v02_fixed_pdo.eds", "Corpus Motion", "Servo with fixed PDOs", 0x100, 0x102, 1, granularity=0)
base_301(e)
pdos(e, map_acc="ro",
     rx_maps=[["0x60400010", "0x60600008"], ["0x607A0020", "0x60FF0020"], ["0x60810020", "0x60830020"],
              ["0x60840020"]],
     tx_maps=[["0x60410010", "0x60610008", "0x603F0010"], ["0x60640020", "0x606C0020"], ["0x60770010"], []])
drive(e, ALL)
e.comment = "Vendor variation: fixed (non-remappable) PDO mapping, Granularity=0, mapping objects ro."
files[e.file] = e.text()

# 03: only PP and HM.
e = Eds("v03_pp_hm_only.eds", "Corpus Motion", "Positioner PP HM", 0x100, 0x103, 1)
base_301(e)
pdos(e)
drive(e, (1 << 0) | (1 << 5))
e.comment = "Vendor variation: a positioner with profile position and homing only (0x6502 = 0x21)."
files[e.file] = e.text()

# 04: two PDOs per direction, four entries each.
e = Eds("v04_four_entries.eds", "Corpus Motion", "Servo 4-entry PDOs", 0x100, 0x104, 1, rx=2, tx=2)
base_301(e)
pdos(e, rx=2, tx=2, slots=4)
drive(e, ALL)
e.comment = "Vendor variation: two PDOs per direction with at most four mapped objects each."
files[e.file] = e.text()

# 05: 16-bit position, velocity and profile objects.
e = Eds("v05_16bit.eds", "Corpus Motion", "Small 16-bit servo", 0x100, 0x105, 1)
base_301(e)
pdos(e)
drive(e, ALL, bits16=True)
e.comment = "Vendor variation: 16-bit position, velocity and profile objects (INTEGER16 / UNSIGNED16)."
files[e.file] = e.text()

# 06: many manufacturer-specific objects in 0x2000..0x5FFF.
e = Eds("v06_manufacturer.eds", "Corpus Motion", "Servo with vendor objects", 0x100, 0x106, 1)
base_301(e)
pdos(e)
drive(e, ALL)
e.add(0x2000, var("Motor type", VS, "rw", "AC servo 400V"))
e.add(0x2001, var("Rated current mA", U32, "rw", "3500", low="0", high="100000"))
e.add(0x2002, var("Speed gain", R32, "rw", "1.25"))
e.add(0x2003, var("Firmware blob", DOM, "rw"))
e.add(0x2004, var("Energy counter", I64, "ro", "0"))
e.record(0x2010, "Current loop", [var("Number of entries", U8, "ro", "3"), var("Kp", U16, "rw", "120"),
                                  var("Ti us", U16, "rw", "800"), var("Limit", I32, "rw", "-1")])
e.compact(0x2020, "Analog inputs", I16, "ro", 4)
e.add(0x3000, var("Brake delay ms", U16, "rw", "50", pdo=1))
e.add(0x4000, var("Vendor status", U32, "ro", "0", pdo=1))
e.add(0x5FFF, var("Vendor service", U8, "rw", "0"))
e.comment = "Vendor variation: manufacturer-specific objects of many kinds in 0x2000..0x5FFF."
files[e.file] = e.text()

# 07: a DCF with PDO ParameterValues (written with the CiA 301 sequence at boot).
e = Eds("v07_pdo_params.dcf", "Corpus Motion", "Servo commissioned", 0x100, 0x107, 1)
base_301(e)
for n in range(4):
    rx_pv = {1: f"$NODEID+0x{0x200 + 0x100 * n:X}" if n < 2 else f"0x{0x80000200 + 0x100 * n:X}+$NODEID", 2: "1"}
    tx_pv = {1: f"$NODEID+0x{0x180 + 0x100 * n:X}" if n < 2 else f"0x{0x80000180 + 0x100 * n:X}+$NODEID", 2: "1"}
    comm(e, 0x1400 + n, f"$NODEID+0x{0x200 + 0x100 * n:X}", rx=True, pv=rx_pv)
    comm(e, 0x1800 + n, f"$NODEID+0x{0x180 + 0x100 * n:X}", rx=False, pv=tx_pv)
rx_maps = [["0x60400010", "0x60600008", "0x607A0020"], ["0x60FF0020", "0x60810020"], [], []]
tx_maps = [["0x60410010", "0x60610008", "0x603F0010"], ["0x60640020", "0x606C0020"], [], []]
for n in range(4):
    mapping(e, 0x1600 + n, [], 8, pv={0: str(len(rx_maps[n])), **{i + 1: v for i, v in enumerate(rx_maps[n])}})
    mapping(e, 0x1A00 + n, [], 8, pv={0: str(len(tx_maps[n])), **{i + 1: v for i, v in enumerate(tx_maps[n])}})
drive(e, ALL)
e.objects[0x6065][0]["ParameterValue"] = "30000"
e.objects[0x6067][0]["ParameterValue"] = "15"
e.commissioning = {"NodeID": "3", "NodeName": "axis_x", "Baudrate": "500", "NetNumber": "1", "CANopenManager": "0"}
e.comment = "Vendor variation: a DCF with PDO ParameterValues and other commissioned values."
files[e.file] = e.text()

# 08: COB-IDs as $NODEID expressions in several spellings.
e = Eds("v08_nodeid_cobs.eds", "Corpus Motion", "Servo NODEID COB-IDs", 0x100, 0x108, 1)
base_301(e)
styles = iter(["$NODEID+0x{:X}", "0x{:X}+$NODEID", "$nodeid + 0x{:X}", "$NODEID+{:d}"] * 2)
pdos(e, cob_style=lambda base: next(styles).format(base))
drive(e, ALL)
e.comment = "Vendor variation: COB-IDs written as $NODEID expressions in several spellings."
files[e.file] = e.text()

# 09: CompactSubObj arrays with Name / Value sections.
e = Eds("v09_compact.eds", "Corpus Motion", "Servo compact arrays", 0x100, 0x109, 1)
base_301(e, heartbeat=False)
e.compact(0x1003, "Pre-defined error field", U32, "ro", 8, names={1: "Newest error"})
e.compact(0x1016, "Consumer heartbeat time", U32, "rw", 4, names={1: "Master", 2: "Axis 2"},
          values={2: "0x00020000"})
e.add(0x1017, var("Producer heartbeat time", U16, "rw", "0"))
pdos(e)
drive(e, ALL)
e.compact(0x2100, "Cam table", I32, "rw", 16)
e.comment = "Vendor variation: CompactSubObj arrays with [xxxxName] / [xxxxValue] sections."
files[e.file] = e.text()

# 12: one PDO per direction (the rest goes by SDO).
e = Eds("v12_one_pdo.eds", "Corpus Motion", "Servo one PDO", 0x100, 0x10C, 1, rx=1, tx=1)
base_301(e)
pdos(e, rx=1, tx=1)
drive(e, ALL)
e.comment = "Vendor variation: a single RPDO and TPDO; what does not fit goes by SDO."
files[e.file] = e.text()

# 13: node guarding only, no heartbeat producer.
e = Eds("v13_guarding_only.eds", "Corpus Motion", "Legacy servo guarding", 0x100, 0x10D, 1)
base_301(e, heartbeat=False, guarding=True)
pdos(e)
drive(e, ALL)
e.comment = "Vendor variation: a legacy drive with node guarding (0x100C/0x100D) and no heartbeat."
files[e.file] = e.text()

# 14: not a drive: a CiA 401 I/O module.
e = Eds("v14_io_module.eds", "Corpus IO", "Digital IO 16/16", 0x200, 0x401, 1)
base_301(e, device_type="0x000F0191")
pdos(e, rx=1, tx=1, rx_maps=[["0x62000108", "0x62000208"]], tx_maps=[["0x60000108", "0x60000208"]])
e.record(0x6000, "Read input 8 bit", [var("Number of entries", U8, "ro", "2"), var("Input 1", U8, "ro", "0", pdo=1),
                                       var("Input 2", U8, "ro", "0", pdo=1)], obj_type="0x8")
e.record(0x6200, "Write output 8 bit", [var("Number of entries", U8, "ro", "2"), var("Output 1", U8, "rw", "0", pdo=1),
                                        var("Output 2", U8, "rw", "0", pdo=1)], obj_type="0x8")
e.comment = "Not a drive: a CiA 401 I/O module. A CiA 402 axis on it must fail at once."
files[e.file] = e.text()

# 10: mixed-case keys (derived from the v01-like drive text).
e = Eds("v10_mixed_case.eds", "Corpus Motion", "Servo mixed case", 0x100, 0x10A, 1)
base_301(e)
pdos(e)
drive(e, ALL)
e.comment = "Vendor variation: keys in mixed case, as some editors write them."
t = e.text()
for k, v in (("ParameterName=", "parameterName="), ("DataType=", "DATATYPE="), ("AccessType=rw", "accesstype=RW"),
             ("AccessType=ro", "Accesstype=RO"), ("PDOMapping=", "PdoMapping="), ("DefaultValue=", "defaultvalue="),
             ("SubNumber=", "subnumber="), ("ObjectType=", "objecttype=")):
    t = t.replace(k, v)
files[e.file] = t

# 11: comments, blank-line oddities, inline comments, CRLF, tabs, a duplicate section and an
# object outside the object lists.
e = Eds("v11_comments.eds", "Corpus Motion", "Servo messy text", 0x100, 0x10B, 1)
base_301(e)
pdos(e)
drive(e, ALL)
e.comment = "Vendor variation: comments, blank lines with blanks, inline comments, CRLF, tabs,\n" \
            "a duplicate section and an object outside the object lists."
t = e.text()
t = t.replace("[6041]\n", "; statusword follows\n   \n[6041]\n# a hash comment\n")
t = t.replace("DefaultValue=20000\n", "DefaultValue=20000    ; counts\n", 1)
t = t.replace("AccessType=rww\n", "AccessType\t=\trww\n", 2)
t += "\n\n\t\n[6085]\nDefaultValue=60000\n\n[2222]\nParameterName=Unlisted vendor object\nObjectType=0x7\n" \
     "DataType=0x0006\nAccessType=rw\nDefaultValue=7\nPDOMapping=0\n"
files[e.file] = "\ufeff".encode("utf-8").decode("utf-8") + t.replace("\n", "\r\n")

for name, text in files.items():
    with open(os.path.join(HERE, name), "w", encoding="utf-8", newline="") as f:
        f.write(text)
print(f"wrote {len(files)} files")
