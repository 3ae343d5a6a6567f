import json
def q(s): return json.dumps(s, ensure_ascii=False)
o=[]
o.append("""# SPDX-License-Identifier: MIT
# SINUMERIK System 3 ELG machine data (words, bits, SSFK flags), setting data, service data and
# R parameters (ch. 5, 12.1, 12.2). Generated from the digest tables by hand-checked script; part of
# sinumerik-elg.yaml. "*" parameters exist per axis (* = axis number − 1 = 0…3): MD 396* → MD3960…MD3963.
device: sinumerik-elg
parameters:
""")
# general MD words
ovr=[1,2,4,6,8,10,20,40,60,70,80,90,100,110,120]
for i,md in enumerate(range(100,115)):
    o.append(f"  - {{id: MD{md}, number: {md}, group: MD words, name: {q(f'Feed override position {i+2}')}, meaning: \"Feed/rapid override in % for switch position {i+2} (0 % = hard stop)\", takes_effect: immediately, fields: [{{name: percent, unit: \"%\", format: \"+9\", range: [0, 130], default: {ovr[i]}}}]}}\n")
gen=[(155,'Increase in scanning time','Position-controller scanning time increase',0,[0,4],'0.5 ms',None),
     (156,'Delay position controller','Time until the controller-enable relays drop after a fault',500,[0,1000],'ms',None),
     (166,'Gearing-On tolerance','Tolerance for engaging the gearing',100,[0,10000],'MS units',None),
     (167,'Threshold value for adaptive precontrol','Threshold of the adaptive pre-control',10,[0,100],'MS units',None),
     (168,'Following error compensation factor','Factor of the following-error compensation',500,[0,1000],'0.1 %',None),
     (169,'Tolerance band, following error monitoring','Machine-dependent minimum of the following-error limit L = max(MD 169, R40)',20,[0,10000],'MS units',None),
     (170,'Speed, semi-automatic centring','Speed of the HAE semi-automatic centring',1000,[0,30000],'1/1000 rpm',None)]
for md,name,meaning,dflt,rng,unit,_ in gen:
    o.append(f"  - {{id: MD{md}, number: {md}, group: MD words, name: {q(name)}, meaning: {q(meaning)}, fields: [{{name: value, unit: {q(unit)}, format: \"+9\", range: {rng}, default: {dflt}}}]}}\n")
o.append("  - {id: MD171, number: 171, group: MD words, name: Current software status number, meaning: Software version number (display only), protection: read_only, fields: [{name: value, format: \"+9\", range: [0, 999999999]}]}\n")
# axis MD words
ax=[(204,'Coarse-stop (exact positioning) tolerance','Limit to accuracy for exact positioning',100,'0, 32000','MS units'),
    (212,'Jamming tolerance','Standstill/jamming limit; must be > MD 204* (alarm 112*)',100,'0, 32000','MS units'),
    (216,'Tolerance band, zero mark monitoring','Zero-mark monitoring band (fixed 0 in 06.85)',0,'0, 0','MS units'),
    (220,'Backlash compensation','Backlash added on direction reversal',0,'-255, 255','MS units'),
    (240,'Reference point coordinates','Reference point coordinate',0,'-99999999, 99999999','MS units'),
    (244,'Zero offset','Zero offset of the axis',0,'-9999, 9999','MS units'),
    (252,'Contour approach (traverse) factor','Position loop gain; must be >= 200 (alarm 2200 on the compute request)',1666,'0, 10000','0.01 1/s'),
    (256,'Partial actual value factor','Should be 0; > 2 risks alarm 108* (overflow in gear factor)',0,'0, 16','0.5 units'),
    (260,'Mult gain','Multiplicative gain CX = 3·10^7 · Umax[V] / (Vmax[1000 units/min] · 10 V); 2400 = 8 V at 10 000',2400,'0, 32000','CX'),
    (264,'Threshold for drive errors','Must be > MD 268* (alarm 156*)',8192,'0, 16000','VELO'),
    (268,'Max. speed set value','DAC limit (alarm 104*); ±1 VELO = ±10 V / DAC number',8192,'0, 16000','VELO'),
    (272,'Drift compensation','Drift compensation value',0,'0, 500','VELO'),
    (276,'Acceleration','Axis acceleration',50,'0, 2000','10000 units/s²'),
    (280,'Max. speed','Axis maximum speed (alarm 2035)',10000,'0, 24000','1000 units/min'),
    (284,'Reference point interrupt (cut-off) speed','Reference point cut-off speed',300,'0, 15000','1000 units/min'),
    (288,'Conventional (JOG) speed','JOG speed',2000,'0, 15000','1000 units/min'),
    (292,'Conventional rapid traverse','Rapid traverse in JOG',10000,'0, 15000','1000 units/min'),
    (296,'Reference point approach rate','Reference point approach speed',10000,'0, 15000','1000 units/min'),
    (300,'Rate of incremental feed','INC feed rate',500,'0, 15000','1000 units/min'),
    (312,'Precontrol factor','Pre-control factor',10000,'0, 16000','-'),
    (316,'Pointer address, + direction, in SSFK table','SSFK table pointer for the + direction',0,'0, 6249','-'),
    (320,'Pointer address, - direction, in SSFK table','SSFK table pointer for the - direction',0,'0, 6249','-'),
    (324,'Distance between 2 SSFK points','SSFK point spacing',0,'0, 32000','MS units'),
    (328,'Compensation value for SSFK','SSFK compensation step',0,'0, 100','MS units'),
    (332,'Tolerance band, contour monitoring','Contour monitoring band (alarm 116*)',1000,'0, 32000','MS units'),
    (336,'Threshold rate, contour monitoring','Contour monitoring threshold speed',0,'0, 24000','1000 units/min'),
    (396,'Number of pick-up pulses per axis revolution (N00/N02)','Pulses per axis revolution before ×4 evaluation; MS = 360/(4·MD 396*) °; maximum input 2 000 000 (alarm 2200)',180000,'0, 2000000','pulses')]
o.append("""  - id: MD200*
    pattern: "MD200{axis}"
    instances: {axis: [0, 1, 2, 3]}
    number: 200
    group: MD words
    name: Axis assignment (measuring circuit / input)
    meaning: "0xMP00: M = measuring-circuit module (1-2), P = actual-value input on it (1-3); value > 2300H raises alarm 8. Defaults 1100H, 1200H, 1300H, 2100H."
    note: "[I] encoding reconstructed (footnote 6 drawing missing)"
    variants:
      - {when: "axis == 0", fields: [{name: assignment, type: hex, digits: 4, range: [0, 0x2300], default: "1100"}]}
      - {when: "axis == 1", fields: [{name: assignment, type: hex, digits: 4, range: [0, 0x2300], default: "1200"}]}
      - {when: "axis == 2", fields: [{name: assignment, type: hex, digits: 4, range: [0, 0x2300], default: "1300"}]}
      - {when: "axis == 3", fields: [{name: assignment, type: hex, digits: 4, range: [0, 0x2300], default: "2100"}]}
""")
for md,name,meaning,dflt,rng,unit in ax:
    o.append(f"  - {{id: \"MD{md}*\", pattern: \"MD{md}{{axis}}\", instances: {{axis: [0, 1, 2, 3]}}, number: {md}, group: MD words, name: {q(name)}, meaning: {q(meaning)}, fields: [{{name: value, unit: {q(unit)}, format: \"+9\", range: [{rng}], default: {dflt}}}]}}\n")
# MD bits
def bits(fields):
    return "{width: 8, fields: [" + ", ".join("{name: %s, bit: %d, width: %d, meaning: %s}"%(n,b,w,q(m)) for n,b,w,m in fields) + "]}"
mdbits=[(5002,'Units of measuring and input system','Bits 2-0 measuring system unit, bits 6-4 input system unit; only 010/010 (22H: MS 0.5 µm, IS 1 µm) is released; an invalid combination raises alarm 4 and the factor 1 is used','00100010',[('measuring_unit',0,3,'000 0.5·10^-2 mm, 001 0.5·10^-3 inch, 010 0.5·10^-3 mm (released), 011 0.5·10^-4 inch, 100 0.5·10^-4 mm, 101 0.5·10^-5 inch, 110 2·10^-4 mm, 111 2·10^-5 inch'),('input_unit',4,3,'000 10^-2 mm, 001 10^-3 inch, 010 10^-3 mm (released), 011 10^-4 inch, 100 10^-4 mm, 101 10^-5 inch')]),
        (5004,'Machine data are input','Bit 7 = machine data are input','10000000',[('md_input',7,1,'machine data are input')]),
        (5016,'Pre-control and SSFK','Bit 0 precontrol active, bit 1 SSFK active, bit 2 direction-dependent SSFK (a different object from SD 5016)','00000001',[('precontrol',0,1,'precontrol active'),('ssfk',1,1,'SSFK active'),('ssfk_direction',2,1,'direction-dependent SSFK')]),
        (5020,'Guide axis B / drive axis C numbers','Bits 7-4 guide axis B number, bits 3-0 drive axis C number (0 none, 1-4 axis)','00010010',[('drive_axis',0,4,'drive axis C number'),('guide_axis',4,4,'guide axis B number')]),
        (5021,'Differential axes Y / Z numbers','Bits 7-4 tangential differential axis Y, bits 3-0 axial differential axis Z','00000000',[('axial_z',0,4,'axial differential axis Z number'),('tangential_y',4,4,'tangential differential axis Y number')]),
        (5022,'NC number / alarm 2215 output','Bits 7-4 NC number for actual value transfer (0 none, 1 NC1, 2 NC2); bits 3-0 axis number of the set-value output whose controller-enable contact signals alarm 2215','00000000',[('contact_axis',0,4,'set-value output for the alarm 2215 contact'),('nc_number',4,4,'NC number for actual value transfer')]),
        (5023,'Feed and compensation functions','Bit 0 feed related to tool revolution, bit 1 following error compensation active, bit 2 optional actual value transfer active','00000000',[('feed_per_tool_rev',0,1,'feed related to tool revolution'),('fe_compensation',1,1,'following error compensation active'),('actual_value_transfer',2,1,'"optical" (optional) actual value transfer active')])]
for md,name,meaning,dflt,flds in mdbits:
    o.append(f"  - {{id: MD{md}, number: {md}, group: MD bits, name: {q(name)}, meaning: {q(meaning)}, fields: [{{name: bits, type: bits, binary: true, bits: {bits(flds)}, default: \"{dflt}\"}}]}}\n")
o.append("  - {id: \"MD560*\", pattern: \"MD560{axis}\", instances: {axis: [0, 1, 2, 3]}, number: 560, group: MD bits, name: Axis display bits, meaning: \"Bit 0 deactivate MX (measuring circuit) monitoring, bit 2 whole degrees, bit 3 radius axis, bit 7 modulo 360° actual value display\", fields: [{name: bits, type: bits, binary: true, bits: " + bits([('no_mx_monitoring',0,1,'deactivate measuring circuit monitoring'),('whole_degrees',2,1,'whole degrees'),('radius_axis',3,1,'radius axis'),('modulo_360',7,1,'modulo 360° actual value display')]) + ", default: \"00000000\"}]}\n")
o.append("  - {id: \"MD564*\", pattern: \"MD564{axis}\", instances: {axis: [0, 1, 2, 3]}, number: 564, group: MD bits, name: Axis bits, meaning: \"Bit 0 reference point in minus direction, 1 change sign of set value, 2 change sign of actual value, 3 partial actual value ×2, 4 partial actual value /2, 5 axis of rotation, 6 partial actual value factor active, 7 axis in existence\", note: \"The 12.1 text calls bit 5 a partial-value bit; the table's 'axis of rotation' is kept\", fields: [{name: bits, type: bits, binary: true, bits: " + bits([('ref_minus',0,1,'reference point in minus direction'),('invert_set',1,1,'change sign of set value'),('invert_actual',2,1,'change sign of actual value'),('partial_x2',3,1,'partial actual value ×2'),('partial_half',4,1,'partial actual value /2'),('rotary',5,1,'axis of rotation'),('partial_active',6,1,'partial actual value factor active'),('exists',7,1,'axis in existence')]) + ", default: \"10100000\"}]}\n")
# SSFK flags
inst=", ".join(str(i) for i in range(6000,6250))
o.append("  - id: \"MD6000-6249\"\n    pattern: \"MD{byte}\"\n    instances: {byte: [" + inst + "]}\n    number: 6000\n    group: SSFK flags\n    name: SSFK compensation flags\n    meaning: \"4 points per byte (byte 6000 = points 4, 3, 2, 1 in bit pairs 7/6, 5/4, 3/2, 1/0; byte 6249 = points 1000…997). Per point: upper bit sign (0 = −, 1 = +), lower bit yes/no (0 = yes, 1 = no).\"\n    note: \"[I] upper bit = sign, lower bit = yes/no, following the label order\"\n    fields: [{name: bits, type: bits, binary: true, bits: " + bits([('p1_no',0,1,'first point of the byte: 1 = no compensation'),('p1_plus',1,1,'first point: 1 = + direction'),('p2_no',2,1,'second point: no'),('p2_plus',3,1,'second point: +'),('p3_no',4,1,'third point: no'),('p3_plus',5,1,'third point: +'),('p4_no',6,1,'fourth point: no'),('p4_plus',7,1,'fourth point: +')]) + ", default: \"01010101\"}]\n")
# SD bits
o.append("  - {id: SD5000-5009, pattern: \"SD{byte}\", instances: {byte: [5000, 5001, 5002, 5003, 5004, 5005, 5006, 5007, 5008, 5009]}, number: 5000, group: SD bits, name: Setting data (not described), meaning: \"Not described in the manual; the block-parity enable probably lives here\", note: \"[I] carried unchanged\", fields: [{name: bits, type: bits, binary: true, bits: {width: 8, allow_unnamed: true, fields: []}, default: \"00000000\"}]}\n")
eq="{0: \"00H line-controlled (RTS/CTS/DSR/DTR)\", 1: \"01H Xon/Xoff character-controlled\", 2: \"02H Siemens System 3/8 reader\", 3: \"03H Siemens PD/PF programming station\"}"
tf=bits([('baud',0,4,'0 = 110, 1 = 150, 2 = 300, 3 = 600, 4 = 1200, 5 = 2400, 6 = 4800, 7 = 9600 Bd (8-15 undefined)'),('parity_bit',4,1,'1 = add a 9th parity bit'),('parity_odd',5,1,'0 = even, 1 = odd'),('stop_bits',6,2,'00 = 1, 01 = 1, 10 = 1.5, 11 = 2')])
o.append(f"  - {{id: SD5010, number: 5010, group: SD bits, name: Equipment coding, data input, meaning: Peripheral type for input, takes_effect: immediately, fields: [{{name: code, type: choice, format: \"+9\", choices: {eq}, default: 0}}]}}\n")
o.append(f"  - {{id: SD5011, number: 5011, group: SD bits, name: Transfer format, data input, meaning: \"Bits 3-0 baud, bit 4 parity bit, bit 5 parity type, bits 7-6 stop bits (C2H = 2 stop, no parity, 300 Bd)\", takes_effect: immediately, fields: [{{name: format, type: bits, binary: true, bits: {tf}, default: \"11000010\"}}]}}\n")
o.append(f"  - {{id: SD5012, number: 5012, group: SD bits, name: Equipment coding, data output, meaning: Peripheral type for output, takes_effect: immediately, fields: [{{name: code, type: choice, format: \"+9\", choices: {eq}, default: 0}}]}}\n")
o.append(f"  - {{id: SD5013, number: 5013, group: SD bits, name: Transfer format, data output, meaning: Same layout as SD 5011, takes_effect: immediately, fields: [{{name: format, type: bits, binary: true, bits: {tf}, default: \"11000010\"}}]}}\n")
o.append("  - {id: SD5014, number: 5014, group: SD bits, name: Xon (start) character, meaning: \"Compared and sent as-is, 8 bits including ISO parity (DC1 = 11H)\", takes_effect: immediately, fields: [{name: char, type: bits, binary: true, bits: {width: 8, fields: [{name: char, bit: 0, width: 8}]}, default: \"00000000\"}]}\n")
o.append("  - {id: SD5015, number: 5015, group: SD bits, name: Xoff (stop) character, meaning: \"Compared and sent as-is, 8 bits including ISO parity (DC3 = 93H)\", takes_effect: immediately, fields: [{name: char, type: bits, binary: true, bits: {width: 8, fields: [{name: char, bit: 0, width: 8}]}, default: \"00000000\"}]}\n")
m1=bits([('no_trailer',1,1,'output without trailer'),('dsr',2,1,'interpret DSR readiness (alarm 19 if low)'),('stop_at_end_char',3,1,'input stops at the SD 5026 character instead of M02/M30'),('eia',4,1,'output in EIA code (should always be 0)'),('crlf',5,1,'block end CR LF instead of LF CR CR'),('no_first_xon',7,1,'start output without waiting for Xon')])
m2=bits([('no_trailer',0,1,'output without trailer'),('dsr',1,1,'interpret DSR readiness'),('stop_at_end_char',2,1,'stop at the end-of-transfer character'),('eia',4,1,'output in EIA code'),('crlf',6,1,'block end CR LF'),('no_first_xon',7,1,'start output without Xon')])
o.append(f"""  - id: SD5016
    number: 5016
    group: SD bits
    name: Special bits (V.24)
    takes_effect: immediately
    note: "The manual disagrees on the bit positions; setting sd5016_map chooses 10.4.2.1 (default) or 12.2"
    variants:
      - {{when: "sd5016_map == '10.4.2.1'", meaning: "Mapping of 10.4.2.1 (prose): bit 1 without trailer, 2 DSR, 3 stop at SD 5026 character, 4 EIA, 5 CR LF, 7 start without Xon", fields: [{{name: bits, type: bits, binary: true, bits: {m1}, default: "00000000"}}]}}
      - {{when: "sd5016_map == '12.2'", meaning: "Mapping of the 12.2 table: bit 0 without trailer, 1 DSR, 2 stop at end character, 4 EIA, 6 CR LF, 7 start without Xon", fields: [{{name: bits, type: bits, binary: true, bits: {m2}, default: "00000000"}}]}}
""")
o.append("  - {id: SD5026, number: 5026, group: SD bits, name: End of transfer character, meaning: \"ISO (or EIA) character ending the input when SD 5016 'stop at end character' is set (ETX = 03H)\", takes_effect: immediately, fields: [{name: char, type: bits, binary: true, bits: {width: 8, fields: [{name: char, bit: 0, width: 8}]}, default: \"00000000\"}]}\n")
# service data
for no,name,unit in [(8000,'Drive axis following error','0.5 units (MS)'),(8001,'Drive axis speed set value','VELO'),(8002,'Adaptive precontrol factor','-')]:
    o.append(f"  - {{id: SD{no}, aliases: [\"SV{no}\"], number: {no}, group: service data, name: {q(name)}, meaning: \"Service datum, display only (data channel code 10, rel. addr. {str(no)[2:]}/{str(no)[:2]})\", protection: read_only, fields: [{{name: value, unit: {q(unit)}, format: \"+9\", range: [-999999999, 999999999]}}]}}\n")
# R parameters
special={20:('Z0: hob threads / shaper cutter teeth','Number of hob threads or shaper cutter teeth, negative for up milling (display Z0)','1','-999','999','3',0,0),
         21:('Z2: workpiece teeth','Number of workpiece teeth (Z2 = 0 gives alarm 2203)','1','2','999','3',0,10),
         40:('TOLER: maximum following error','Maximum following error for the monitoring; not accepted below MD 169 (the last valid limit stays)','MS units','0','10000','5',0,50),
         60:('TANG (Udy): differential component, tangential','Tangential differential component','°/mm or °/0.1 inch','-999.99999','999.99999','3',5,0),
         61:('AXIAL (Udz): differential component, axial','Axial differential component','°/mm or °/0.1 inch','-999.99999','999.99999','3',5,0)}
rest=[i for i in range(100) if i not in special]
o.append("  - {id: Rxx, pattern: \"R{n}\", instances: {n: [" + ", ".join(str(i) for i in rest) + "]}, number: 0, group: R parameters, name: R parameter, meaning: \"General R parameter (PC-ELG data channel code 09, format ±99999.999 with a variable decimal point)\", takes_effect: immediately, fields: [{name: value, format: \"+5.3\", default: 0}]}\n")
for n,(name,meaning,unit,lo,hi,idig,dec,dflt) in special.items():
    fmt=f"+{idig}.{dec}" if dec else f"+{idig}"
    o.append(f"  - {{id: R{n}, number: {n}, group: R parameters, name: {q(name)}, meaning: {q(meaning)}, takes_effect: immediately, fields: [{{name: value, unit: {q(unit)}, format: \"{fmt}\", range: [{lo}, {hi}], default: {dflt}}}]}}\n")
open('/work/wt/profiles/profiles/devices/sinumerik-elg/data.yaml','w').write(''.join(o))
