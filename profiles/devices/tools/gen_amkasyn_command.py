# Generates profiles/devices/amkasyn-sf/command.yaml (FB 208 commanding DB per SF type) and
# init.yaml (FB 207 initialisation DB) from the digest's tables (shared/seeds/amkasyn-sf.md §1.5, §3).
import json
from fractions import Fraction as F
def q(s): return json.dumps(s, ensure_ascii=False)
def num(x):
    x=F(x)
    if x.denominator==1: return str(x.numerator)
    # exact decimal
    from decimal import Decimal, getcontext
    getcontext().prec=40
    return format(Decimal(x.numerator)/Decimal(x.denominator),'f').rstrip('0').rstrip('.')
params={}   # addr -> list of variants (dicts)
order=[]
def add(addr, when, name, meaning='', unit='', lo=None, hi=None, lsb=None, values=None, choices=None, bits=None, default=None, note='', signed=None):
    kind=addr[:2]
    if addr not in params: params[addr]=[]; order.append(addr)
    params[addr].append(dict(when=when,name=name,meaning=meaning,unit=unit,lo=lo,hi=hi,lsb=lsb,values=values,choices=choices,bits=bits,default=default,note=note,signed=signed))
def field_yaml(addr, v):
    kind=addr[:2]; word=int(addr[2:])
    parts=[f"name: {q(v['name'].lower().replace(' ','_').replace('/','_').replace('(','').replace(')','').replace('.','').replace(',','').replace('-','_')[:40])}"]
    if v['unit']: parts.append(f"unit: {q(v['unit'])}")
    parts.append(f"word: {word}")
    lsb=v['lsb']
    if kind in ('DR','DL'):
        parts.append(f"encoding: {kind}")
    else:
        parts.append("encoding: fixed")
        parts.append(f"word_bits: {32 if kind=='DD' else 16}")
        signed = v['signed'] if v['signed'] is not None else True
        parts.append(f"signed: {'true' if signed else 'false'}")
    if lsb is not None: parts.append(f"lsb: {q(str(lsb))}")
    scale=F(lsb) if (lsb is not None and '/' not in str(lsb)) else (F(str(lsb)) if lsb is not None else F(1))
    if v['choices'] is not None:
        parts.append("type: choice")
        parts.append("choices: {" + ", ".join(f"{k}: {q(t)}" for k,t in v['choices'].items()) + "}")
    if v['bits'] is not None:
        width = 8 if kind in ('DR','DL') else (32 if kind=='DD' else 16)
        parts.append("type: bits")
        parts.append("bits: {width: %d, fields: [%s]}" % (width, ", ".join("{name: %s, bit: %d, width: %d, meaning: %s}"%(n,b,w,q(m)) for n,b,w,m in v['bits'])))
    if v['values'] is not None:
        parts.append("values: [" + ", ".join(num(F(x)*scale) for x in v['values']) + "]")
    if v['lo'] is not None or v['hi'] is not None:
        lo = v['lo']; hi = v['hi']
        def b(x):
            if isinstance(x,str): return q(x)
            return num(F(x)*scale)
        rng = "{" + ", ".join(p for p in [f"min: {b(lo)}" if lo is not None else None, f"max: {b(hi)}" if hi is not None else None] if p) + "}"
        parts.append(f"range: {rng}")
    d=v['default'] if v['default'] is not None else (v['values'][0] if v['values'] else (v['lo'] if isinstance(v['lo'],int) and v['lo']>0 else 0))
    if v['choices'] is not None and v['default'] is None: d=list(v['choices'].keys())[0]
    parts.append(f"default: {q(num(F(d)*scale))}")
    if v['note']: parts.append(f"note: {q(v['note'])}")
    return "{" + ", ".join(parts) + "}"

T=lambda *ts: "sf_type in [" + ", ".join(str(t) for t in ts) + "]"
HALF="1/2"   # 0.5 ms per LSB
# ---- header -------------------------------------------------------------------------------------
add('DR0', '', 'SF number', 'Slot of the fast function (must equal the FB 207 SF number)', '', 0, 'sf_number_max')
fct = {0:("sf_type == 0", {0:'none',1:'DCOPY direct copy',2:'ECOPY binary-input-dependent copy',255:'SIDIFF following-error monitoring'}),
       3:("sf_type == 3", {1:'VARSYNC variable synchronous ratio',2:'DIGDREH digital speed switch'}),
       8:("sf_type == 8", {0:'no dead-time compensation',1:'dead-time compensation (BA 1 only)'})}
add('DL0', T(0), 'SFKMD fct', 'COPY sub-function', choices=fct[0][1], default=1)
add('DL0', T(1), 'SFKMD fct', 'FIPW function bits', bits=[('printing_mark',0,1,'printing mark control'),('correction_before_sak',1,1,'correction before (1) / after (0) SAK'),('external_sync',2,1,'sync to the external master zero pulse')])
add('DL0', T(3), 'SFKMD fct', 'STDFKT sub-function', choices=fct[3][1], default=1)
add('DL0', T(5), 'SFKMD fct', 'FGEN function bits', bits=[('generator',0,1,'reference generator active'),('zeroing',1,1,'feedback value zeroing active'),('monitoring',2,1,'feedback position monitoring active')], default=1)
add('DL0', T(8), 'SFKMD fct', 'BINEA function', choices=fct[8][1])
add('DL0', T(9), 'SFKMD fct', 'XFIPW function bits', bits=[('printing_mark',0,1,'printing mark control'),('correction_before_sak',1,1,'correction before SAK'),('external_sync',2,1,'sync on the external master at START'),('setting_on',3,1,"'setting on' the master offset angle at START"),('retrigger',4,1,'retriggering by E1 during the movement'),('table_change_every_run',5,1,'table set change after every table run-through')])
add('DL0', T(2,4,6,7,10,11,12), 'SFKMD fct', 'Not used (0)', values=[0], note='DFKT: not described, the example uses 0')
codes={0:'RESET',1:'START',5:'VALUE NEW',6:'READ VALUE'}
def codeset(ks): return {k:codes[k] for k in ks}
add('DR1', "sf_type == 0 && fct == 1", 'SFKMD code', 'Command code', choices=codeset([0,1]))
add('DR1', T(0,4,5,6,7,8,11), 'SFKMD code', 'Command code', choices=codeset([0,1,5]))
add('DR1', T(9), 'SFKMD code', 'Command code (START and READ VALUE only in Reset, VALUE NEW only when started)', choices=codeset([0,1,5,6]))
add('DR1', T(1,2,3,10,12), 'SFKMD code', 'Command code', choices=codeset([0,1]))
fipw_ba={2:'distance, cyclic table processing',26:'distance, start immediately with auto stop',82:'distance, clocking in/out with auto stop',98:'distance, clocking in/out',4:'time, cyclic table processing',132:'time, start immediately with auto stop',84:'time, clocking in/out with auto stop',100:'time, clocking in/out'}
add('DL1', "sf_type == 0 && fct == 1", 'SFKMD-BA', 'DCOPY mode', choices={0:'absolute copy',1:'incremental copy (from V02.11)'})
add('DL1', "sf_type == 0 && fct == 2", 'SFKMD-BA', 'ECOPY: bit0 = for E1 = 0 copy Value_E1_0, bit1 = for E1 = 1 copy Value_E1_1 (else the source)', bits=[('value_for_e1_0',0,1,'E1 = 0: copy DD2 Value_E1_0 instead of the source'),('value_for_e1_1',1,1,'E1 = 1: copy DD4 Value_E1_1 instead of the source')])
add('DL1', "sf_type == 0 && fct == 255", 'SFKMD-BA', 'SIDIFF evaluation', bits=[('eval16',0,1,'16-bit evaluation of Config-AW message32'),('mean16',1,1,'16-bit mean formation')])
add('DL1', "sf_type == 0", 'SFKMD-BA', 'COPY without function', values=[0])
add('DL1', T(1), 'SFKMD-BA', 'FIPW operating mode (enumeration)', choices=fipw_ba, default=2)
add('DL1', T(2), 'SFKMD-BA', 'FIPZ operating mode', choices={16:'edge on Ek starts table k-1',17:'edge on E1 starts the table selected by E2..E4'}, default=16)
add('DL1', "sf_type == 3 && fct == 1", 'SFKMD-BA', 'VARSYNC ratio selection', choices={0:'E1 selects m1/m2 (level)',1:'E1 edge takes m1..m8 from E2..E4',2:'E2E1 select m1..m3 (11 = unchanged)',3:'online ratio from MW/EW'})
add('DL1', "sf_type == 3", 'SFKMD-BA', 'DIGDREH (not used)', values=[0])
add('DL1', T(4), 'SFKMD-BA', 'DFKT mode bits', bits=[('angle_growth',0,1,'input is an angle growth (16-bit) instead of an absolute speed'),('binary_io',1,1,'binary inputs control start/stop and table selection'),('standardised',2,1,'ratio standardised by V_N')])
add('DL1', T(5), 'SFKMD-BA', 'FGEN mode bits', bits=[('external_velocity',0,1,'external velocity from the source'),('sequence',1,1,'sequence mode (else continuous)'),('two_accelerations',2,1,'E2 selects DD6 / DD24')])
add('DL1', T(6), 'SFKMD-BA', 'REGL mode bits', bits=[('switches_from_inputs',0,1,'S1..S3 from E1..E3 (else DW4)'),('external_sync',1,1,'control cycle only on a positive edge of E1 (E4)'),('positive_limit_zero',2,1,'positive output limit = 0'),('negative_limit_zero',3,1,'negative output limit = 0'),('limit_after_sp',4,1,'limitation and amplification after the summation point'),('clear_integrator',5,1,'delete the integrator when S2 opens')])
add('DL1', T(7), 'SFKMD-BA', 'IMES mode bits', bits=[('absolute',0,1,'absolute measurement (else difference)'),('set_down',1,1,'an invalid pulse becomes the new start value'),('positive_limitation',2,1,'positive limitation'),('negative_limitation',3,1,'negative limitation')])
add('DL1', T(8,12), 'SFKMD-BA', 'Operating mode', choices={0:'absolute',1:'incremental',2:'time mode'})
add('DL1', T(9), 'SFKMD-BA', 'XFIPW operating mode (FIPW codes; code + 1 = with table set switch-over)', choices={**{k:v for k,v in fipw_ba.items()}, **{k+1:v+', table set switch-over' for k,v in fipw_ba.items()}}, default=2)
add('DL1', T(10), 'SFKMD-BA', 'APSF (not used)', values=[0])
add('DL1', T(11), 'SFKMD-BA', 'EPOS mode bits', bits=[('external_velocity',0,1,'external velocity'),('substitutional',1,1,'substitutional positioning (else relative)'),('reversal',2,1,'direction reversal enable (substitutional)'),('retrigger',3,1,'retrigger adds travel (bit4 = 0 only)'),('modulo',4,1,'modulo positioning (relative, from V02.13)')])
# ---- COPY ---------------------------------------------------------------------------------------
add('DD2', "sf_type == 0 && fct == 2", 'Value_E1_0', 'Value copied to the sink for E1 = 0 (BA bit0 = 1), sink units', '', -2**31, 2**31-1)
add('DD4', "sf_type == 0 && fct == 2", 'Value_E1_1', 'Value copied to the sink for E1 = 1 (BA bit1 = 1), sink units', '', -2**31, 2**31-1)
add('DR2', "sf_type == 0 && fct == 255", 'AW mask', 'Monitored drives: bit0 = AW1 … bit7 = AW8', '', 0, 255)
add('DL2', "sf_type == 0 && fct == 255", 'reserved', 'Reserved 0', values=[0])
add('DR3', "sf_type == 0 && fct == 255", 'AW number', '0 = no display; 1..8 = corrected difference of AWn to the sink', '', 0, 8)
add('DR4', "sf_type == 0 && fct == 255", 'Mean factor N', '0 = default 10; 1 = no averaging; 2..255', '', 0, 255)
add('DR5', "sf_type == 0 && fct == 255", 'Agreements', 'Consecutive (non-)exceedances before a bit changes; 0 = default 5', '', 0, 255)
# ---- FIPW / XFIPW (types 1, 9) -------------------------------------------------------------------
SAKM="Following-error compensation factor: 0 = off; SAK = 7680000/ID2/ID104 + 128·(1 + 1/ID2) (internal) or + 256 (external)"
add('DW2', T(1,2,9), 'SAK factor', SAKM, '', 0, 32767)
add('DW2', "sf_type == 3 && fct == 1", 'SAK factor', SAKM, '', 0, 32767)
add('DW3', T(1,2,9), 'SF cycle time', 'Must equal drive parameter ID 2', 'ms', 1, 32767, lsb='0.5', default=2)
add('DW4', T(1,9), 'Total table number m', 'Tables (per set for XFIPW)', '', 1, 8, default=1)
add('DW5', T(1,9), 'Start table number q', 'Start tables Tab0..Tab q-1 (q <= m-1)', '', 0, 7)
add('DW6', T(1,2,9), 'Division exponent n', 'Y = interp · K / 2^n', '', 0, 15)
add('DR7', T(1,9), 'MD addr. ext. sync.', 'MD address of the master zero pulse copied by SF COPY (printing mark control + external sync)', '', 0, 124)
add('DL7', T(1), 'reserved', 'Reserved 0', values=[0])
add('DL7', T(9), 'Working table cycles', '0, 1 = once; 2..255 = that many times (modes ending automatically)', '', 0, 255)
add('DD8', T(1,9), 'Multiplication factor K', 'Y = interp · K / 2^n (1 = none, fastest)', '', -2**15, 2**15-1, default=1)
add('DD8', T(2), 'Multiplication factor K', 'FIPZ: +1..+2^15-1', '', 1, 2**15-1, default=1)
add('DD10', "sf_type in [1, 9] && ba in [2, 3, 26, 27, 82, 83, 98, 99]", 'Increments per revolution Xme', 'Master input increments per cycle ("2π")', 'incr', 50, 2**15-1, default=20000, note='The manual names it DW10 in the table and DD10 in the examples; both accepted')
add('DD10', "sf_type in [1, 9]", 'Cycle time Te', 'Table duration in the time modes', 'ms', 1, '32767 * DW3', lsb='0.5', default=2000)
add('DW10', "sf_type in [1, 9] && ba in [2, 3, 26, 27, 82, 83, 98, 99]", 'Increments per revolution Xme', 'Master input increments per cycle (16-bit form of DD10)', 'incr', 50, 2**15-1, default=20000)
add('DW12', T(1), 'Master offset angle', 'Input variable set to this offset at START (0..Xme-1 / 0..Te-1)', 'incr', 0, 32767, signed=True)
add('DW12', T(9), 'Master offset angle', 'Signed: ±(Xme-1) in distance mode (negative = slave lags); time 0..Te-1', 'incr', -32767, 32767)
add('DW14', T(1,9), 'Start angle', 'Clock-in window around 0 (mod Xme); 0 = only at the table start', 'incr', 0, 32767)
add('DW16', T(1,9), 'Stop angle', 'Clock-out window; 0 = only at the table end', 'incr', 0, 32767)
add('DW18', T(1,9), 'Format length', 'Printing mark control: standardisation value in user units (1000 = 100 mm at 0.1 mm)', 'user unit', 0, 32767)
add('DD20', T(1,9), 'Printing mark sensor distance', 'Sensor to synchronous point at shift 0', 'user unit', 0, 2**31-1)
add('DW22', T(1,9), 'Synchronous point shift', '0..format length-1, towards the sensor', 'user unit', 0, 32767)
add('DW23', T(1,9), 'Valid range', 'Window around the mark command position; 0 = whole range (not with RFPAK: use format/2)', 'user unit', 0, 32767)
add('DW24', T(1,9), 'Start angle correction range SK', 'Master angle where the correction output starts', 'incr', 0, 32767)
add('DW25', T(1,9), 'Length correction range LK', '0..Xme-SK; SK = LK = 0 → SK = 3/4 Xme, LK = 1/8 Xme', 'incr', 0, 32767)
add('DW26', T(1,9), 'MD addr. correction value', '0 = no output; 4..124 → dXM in increments to MD', '', 0, 124)
add('DR27', T(1,9), 'Correction weighting k', '0 → F = 1; 1..31 → F = 2^-k; 32 → F = 0; 128 → F = -1; 129..159 → F = -2^(128-k)', '', values=list(range(0,33))+list(range(128,160)))
add('DL27', T(1,9), 'Correction counter n', '0, 1 = every mark; 2..255 = every n-th mark', '', 0, 255)
add('DD32', T(9), 'Output value', 'READ VALUE result: slave position for the master offset angle relative to the 0 point of the 1st table', 'incr', -2**31, 2**31-1)
# ---- FIPZ (type 2) ------------------------------------------------------------------------------
add('DW4', T(2), 'Total table number', 'Tables Tab0..', '', 1, 8, default=1)
for k in range(8):
    add(f'DW{10+k}', T(2), f'Cycle time Tab{k}', f'Duration of table {k}', 'ms', 1, 32767, lsb='0.5', default=200)
# ---- VARSYNC / DIGDREH (type 3) -----------------------------------------------------------------
for k in range(8):
    add(f'DW{4+2*k}', "sf_type == 3 && fct == 1 && ba in [0, 1, 2]", f'Ratio m{k+1}', 'Synchronous ratio, 1/10000 units (10000 = 1.0)', '', -32768, 32767, lsb='0.0001', default=10000 if k<2 else 0, note='m1, m2 used by BA 0..2, m3 by BA 1..2, m4..m8 by BA 1')
add('DW3', "sf_type == 3 && fct == 1 && ba == 3", 'SF cycle time', 'Must equal ID 2', 'ms', 1, 32767, lsb='0.5', default=2)
add('DR4', "sf_type == 3 && fct == 1 && ba == 3", 'Word address', 'MW/EW address of the online ratio (rounded down to even)', '', 0, 255)
add('DL4', "sf_type == 3 && fct == 1 && ba == 3", 'Word attribute', '0 = MW, 1 = EW', choices={0:'MW flag word',1:'EW input word'})
add('DD2', "sf_type == 3 && fct == 2", 'Speed command value n_e', '32-bit speed command (0.0001 rpm per LSB; 100000 = 10 rpm)', 'rpm', -2**31, 2**31-1, lsb='0.0001', note='The manual example uses 1000000 for "1000 rpm" (errata 1): the definition (0.0001 rpm) is kept')
# ---- DFKT (type 4) ------------------------------------------------------------------------------
add('DW3', T(4), 'SF cycle time', 'Only needed in the angle-growth mode', 'ms', 1, 32767, lsb='0.5', default=2)
add('DW4', T(4), 'Number of speed tables', '0 = none, 1..7', '', 0, 7)
add('DW5', T(4), 'Active table', '0 = none (ratio only); 1..7 = Table0..Table6', '', 0, 7)
add('DW6', T(4), 'Division factor of V', '', '', 1, 32767, default=1)
add('DW8', T(4), 'Multiplication factor of V', 'V = DW8 / DW6', '', -32767, 32767, default=1)
add('DW10', T(4), 'Input encoder resolution', 'Angle-growth mode', 'incr', 1, 65535, signed=False, default=1)
add('DW11', T(4), 'Input speed final value n_end', '', 'rpm', 1, 32767, default=1)
add('DW12', T(4), 'Max output speed', '', 'rpm', 0, 32767)
add('DW14', T(4), 'Min output speed', '', 'rpm', -32767, 0)
add('DW16', T(4), 'Max out/in ratio (numerator)', '', '', -32767, 32766)
add('DW18', T(4), 'Min out/in ratio (numerator)', '', '', -32766, 32767)
add('DW20', T(4), 'Ratio division factor', '', '', 1, 32767, default=1)
add('DW22', T(4), 'Continuation below the lower limit', '', choices={0:'limit to the first table value',2:'point mirroring at the origin'})
add('DW23', T(4), 'Continuation above the upper limit', '', choices={0:'limit to the last table value',1:'linear extrapolation'})
# ---- FGEN (type 5) ------------------------------------------------------------------------------
add('DW2', T(5), 'Cycle time', 'Time in which the increments of one "2π" are output', 'ms', 1, 32767, lsb='0.5', default=2000)
add('DW3', T(5,6,7,8,11,12), 'SF cycle time', 'SF cycle (REGL/IMES: currently not used)', 'ms', 1, 131, lsb='0.5', default=2)
add('DD4', T(5), 'Cycle output increments', 'e.g. encoder resolution of the following FIPW', 'incr', 1, 2**31-1, default=20000)
add('DD6', T(5), 'Acceleration', '', 'incr/s²', 1, 500000000, default=100000)
add('DW8', T(5), 'Override flag word address', '0 = none; 2..126 (1024 = 100 %)', '', 0, 126)
add('DW9', T(5), 'AW mask', 'bit0..7 = AW1..8, at most 7 set', '', 0, 255)
for k in range(7):
    add(f'DD{10+2*k}', T(5), f'Position limit {k}', f'Feedback position limit {k} (output A{k+2})', 'incr', 0, 2**31-1)
add('DD24', T(5), 'Acceleration2', 'BA bit2 = 1 and E2 = 1', 'incr/s²', 1, 500000000, default=100000)
# ---- REGL (type 6) ------------------------------------------------------------------------------
add('DW4', T(6), 'Switch bit mask', 'bit0 S1, bit1 S2, bit2 S3 (1 = closed); used when BA bit0 = 0', '', bits=[('s1',0,1,'S1 closed'),('s2',1,1,'S2 closed'),('s3',2,1,'S3 closed (source2 path)')])
add('DR5', T(6), 'Filter type', '', choices={0:'none',1:'mask the 2 LSBs',2:'mean over 4 samples'})
add('DL5', T(6), 'SF source assessment', '', bits=[('negate',0,1,'negate the source'),('no_adc_conversion',1,1,'no 12-bit ADC → two\'s complement conversion')])
add('DW6', T(6), 'Kp', 'Proportional gain (256 = 1.0)', '', 0, 16383, lsb='1/256', default=256)
add('DW7', T(6), 'Ki', 'Integral gain (128 = 0.5); Tn = Tsf·Kp/Ki', '', 0, 16383, lsb='1/256')
add('DW8', T(6), 'Kd', 'Derivative gain (64 = 0.25); Tv = Tsf·Kd/Kp (mislabelled "Kp factor" in the manual)', '', 0, 16383, lsb='1/256')
add('DD10', T(6), 'Output limit y_max', 'Output units', '', 0, 2**30-1)
add('DW12', T(6), 'Output gain v', 'Negative reverses the action; 0 not allowed', '', -2**15, 2**15-1, default=1)
add('DD14', T(6), 'Integration limit i_max', '', '', 0, 2**21-1)
add('DW16', T(6), 'MW address source1', '0 = use DW18; 2..126', '', 0, 126)
add('DW17', T(6), 'MD address source2', '0 = use DD20; 4..124', '', 0, 124)
add('DW18', T(6), 'Command value source1', 'int16', '', -2**15, 2**15-1)
add('DD20', T(6), 'Command value source2', 'int32 (feed-forward)', '', -2**31, 2**31-1)
# ---- IMES (type 7) ------------------------------------------------------------------------------
add('DD4', T(7), 'Command spacing', '0 → output = pulse spacing', 'incr', 0, 2**30-1)
add('DD6', T(7), 'Permissible window', '0 = always valid', 'incr', 0, 2**30-1)
add('DD8', T(7), 'Blocked range', '0 = none', 'incr', 0, 2**30-1)
# ---- BINEA (type 8) -----------------------------------------------------------------------------
add('DW2', T(8), 'Dead time', '0 = none', 'ms', 0, 32000, lsb='0.5')
add('DW4', T(8), 'Tracks', 'from track0', '', 1, 8, default=1)
add('DW5', T(8), 'MW address of the feedback value offset', '0 → DW6; 2..126', '', 0, 126)
add('DW6', T(8), 'Feedback value offset', 'source units', '', -2**15, 2**15-1)
TRACK=[('invert_output',0,1,'invert the output bit'),('invert_input',1,1,'invert the input bit'),('logic',2,2,'00 none, 01 AND with the input, 10 OR'),('monoflop',4,1,'a 0→1 table change starts a monoflop'),('output_off',5,1,'output not updated')]
for k in range(8):
    add(f'DW{8+k}', T(8), f'Mode track{k}', 'Track mode word', bits=TRACK)
add('DW16', T(8), 'Dead time mean factor', '0 → 20; 1 = none; 2..30000 SF cycles', '', 0, 30000)
# ---- APSF (type 10) -----------------------------------------------------------------------------
add('DW3', T(10), 'SF cycle time', 'Unused, 0', values=[0])
add('DW4', T(10), 'FB number', 'User AWL function block', '', 0, 63)
add('DW5', T(10), 'DB number', '0 = none, 1..63', '', 0, 63)
add('DW6', T(10), 'Number of output bits', 'AB 216 bits copied from the output bit mask', '', 0, 8)
# ---- EPOS (type 11) -----------------------------------------------------------------------------
add('DD4', T(11), 'Position command value (travel)', 'relative: per positioning; substitutional: relative to the reference', 'incr', -2**31, 2**31-1)
add('DD6', T(11), 'Velocity', '0.0001 rpm per LSB; relative: magnitude counts; substitutional: sign = approach direction', 'rpm', -(2**31-1), 2**31-1, lsb='0.0001', default=1000000)
add('DD8', T(11), 'Acceleration', '0.001 rev/s² per LSB', 'rev/s²', 1, 10**8, lsb='0.001', default=1000)
add('DD10', T(11), 'Deceleration at stop', '>= DD8', 'rev/s²', 1, 10**8, lsb='0.001', default=1000)
add('DD12', T(11), 'Drive encoder resolution', '', 'incr/rev', 1, 2**31-1, default=20000)
add('DD14', T(11), 'External master encoder resolution', 'external-velocity BA', 'incr/rev', 1, 2**31-1, default=20000)
add('DW16', T(11), 'Velocity override MW address', '0 = none; 2..126 (1024 = 100 %)', '', 0, 126)
add('DW17', T(11), 'Acceleration override MW address', '0 = none; 2..126 (1024 = 100 %, clamped 10..100 %)', '', 0, 126)
# ---- CAM (type 12) ------------------------------------------------------------------------------
add('DW4', T(8 if False else 12), 'Dead time mean factor', '0 → 20; 1 = none; 2..30000 SF cycles', '', 0, 30000)
for k,a in enumerate(['DR6','DL6','DR7','DL7','DR8','DL8','DR9','DL9']):
    add(a, T(12), f'Cams on track{k}', '0 = track unused; sum over all tracks <= 56', '', 0, 56)
for k,a in enumerate(['DR10','DL10','DR11','DL11','DR12','DL12','DR13','DL13']):
    add(a, T(12), f'Mode track{k}', 'bit0 invert out, bit1 invert in, bits3/2 logic, bit4 retriggerable monoflop, bit5 output off', bits=[('invert_output',0,1,'invert the output bit'),('invert_input',1,1,'invert the input bit'),('logic',2,2,'00 none, 01 AND, 10 OR'),('monoflop',4,1,'retriggerable monoflop'),('output_off',5,1,'output off')])
add('DD14', T(12), 'Modulo value', 'BA 1/2 (20000 = one revolution at 20000 incr/rev)', 'incr', 0, 2**30-1)
for k in range(8):
    add(f'DW{16+k}', T(12), f'Hysteresis track{k}', '0 = off; 1..65535 × 100 increments (from V02.13)', 'incr', 0, 65535, lsb='100', signed=False)

out=["# SPDX-License-Identifier: MIT\n# AMKASYN PS fast functions: FB 208 commanding DB (34 words, DW0..DW33) per SF type and function.\n# Generated by the script kept in docs/profiles.md (section AMKASYN) from the digest's tables;\n# values are in the manual's units (lsb converts to the stored integer: 0.5 ms, 1/256, 1/10000,\n# 0.0001 rpm, 0.001 rev/s², 100 increments). Addresses not used by the selected SF are reserved = 0.\n# Part of amkasyn-sf.yaml.\ndevice: amkasyn-sf\nparameters:\n"]
def sort_key(a):
    return (int(a[2:]), {'DR':0,'DL':1,'DW':2,'DD':3}[a[:2]])
allw=[f'DW{i}' for i in range(2,34)]
for a in allw:
    if a not in params: params[a]=[]; order.append(a)
for a in sorted(params, key=sort_key):
    vs=params[a]
    out.append(f"  - id: {a}\n    number: {int(a[2:])}\n    group: commanding DB\n    required: false\n    variants:\n")
    for v in vs:
        when = v['when']
        wl = f"when: {q(when)}, " if when else ""
        out.append(f"      - {{{wl}name: {q(v['name'])}, meaning: {q(v['meaning'] or v['name'])}, takes_effect: immediately, fields: [{field_yaml(a, v)}]}}\n")
    if a.startswith('DW'):
        fv=dict(when='',name='reserved',meaning='',unit='',lo=None,hi=None,lsb=None,values=[0],choices=None,bits=None,default=0,note='',signed=None)
        out.append(f"      - {{name: \"reserved\", meaning: \"Reserved = 0 for this SF type\", takes_effect: immediately, fields: [{field_yaml(a, fv)}]}}\n")
open('/work/wt/profiles/profiles/devices/amkasyn-sf/command.yaml','w').write(''.join(out))
print(len(params),'addresses')
