import re, json
src=open('/work/shared/seeds/ip247.md').read()
def q(s): return json.dumps(s, ensure_ascii=False)
def section(a,b): return src[src.index(a):src.index(b)]
def rows(sec):
    out=[]
    for line in sec.splitlines():
        if not line.startswith('| ') or line.startswith('|---') or line.startswith('| AG |') or line.startswith('| No. |'): continue
        out.append([c.strip() for c in line.strip()[1:-1].split('|')])
    return out
o=["# SPDX-License-Identifier: MIT\n# IP247 error lists (§7.2): module errors (MB251 / DR n+12; COM247 shows 80h + code as Fxx), MD\n# errors (DR n+4 of the MD DB), VP syntax errors (VP DB DW n+3) and the interface byte MB250.\n# German originals as in the manual; English from the digest. Part of ip247.yaml.\ndevice: ip247\ncatalogues:\n"]
o.append("  - id: module\n    title: IP247 module (axis) errors (Baugruppenfehler), AG code = MB251 / DR n+12\n    code_format: dec\n    defaults:\n      reaction: stop\n      acknowledge: \"Latched until acknowledged by the next operating command on either interface; BA17 'clear errors' clears all axes and the data channel\"\n    entries:\n")
sec=section('### 6.1 Module (axis) errors','### 6.2 MD errors')
for c in rows(sec):
    ag,com,de,en=(c+['']*4)[:4]
    if de=='frei': continue
    de=de.replace('★','').strip()
    warn='(W)' in en
    en_clean=en.replace('(W)','').strip()
    text=re.split(r'[:;]',en_clean)[0].strip()
    cause=en_clean
    v=int(ag)
    reaction='message' if (warn or v in (0,4)) else 'stop'
    if v==34: reaction='needs_reset'
    if v==53: reaction='drive_off'
    ack=None
    if warn or v==0: ack="Warning/information: no abort; cleared by the next operating command"
    if v==34: ack="Hardware fault: power cycle; exchange the module if it persists"
    extra=f", acknowledge: {q(ack)}" if ack else ""
    note=f"COM247 display {com}" if com else "AG only"
    if v==16: text="PG offline (COM247 only; free in the AG)"; de="Programmiergerät ist Offline"
    o.append(f"      - {{code: {q(ag)}, text: {q(text[:1].upper()+text[1:])}, text_de: {q(de)}, cause: {q(cause)}, reaction: {reaction}{extra}, note: {q(note)}}}\n")
o.append("  - id: md_error\n    title: IP247 machine-data errors (DR n+4 of the MD DB; COM247 F00-F0F, F60-F66)\n    code_format: dec\n    defaults:\n      reaction: stop\n      acknowledge: \"Correct the MD set: delete it (BA21) and write it again (BA20); the axis stays not ready (module error 14/15) until then\"\n    entries:\n")
sec=section('### 6.2 MD errors','### 6.3 VP syntax errors')
EN={0:'No error (MD OK)',1:'Not yet checked',2:'Wrong pulse duration',3:'Wrong maximum frequency',4:'Wrong jog / incremental speed',5:'Wrong number of pulses per revolution',6:'Wrong frequency increase',7:'Wrong software limit switch',8:'Wrong reference point',9:'Wrong gear ratio',10:'Wrong number of energization patterns',11:'Wrong unit of measure',12:'Wrong module number',13:'Zero offset too large',14:'Wrong tool (length) offset',15:'Wrong value for reference direction (and synchronisation)',16:'Ramp table generated wrongly',17:'Wrong reference speed',18:'Wrong edge evaluation',19:'Wrong polarity of the limit switches',20:'Wrong backlash compensation value',21:'Wrong range end',22:'Wrong start-stop frequency'}
for c in rows(sec):
    no,com,de,cond=(c+['']*4)[:4]
    v=int(no)
    reaction='message' if v in (0,1) else 'stop'
    extra=', acknowledge: "Nothing to acknowledge"' if v==0 else (', acknowledge: "Transfer the set to the module (BA20); the firmware checks it"' if v==1 else '')
    note=f"COM247 display {com}" if com not in ('–','') else "no COM247 code"
    o.append(f"      - {{code: {q(no)}, text: {q(EN[v])}, text_de: {q(de)}, cause: {q(cond)}, reaction: {reaction}{extra}, note: {q(note)}}}\n")
o.append("  - id: syntax\n    title: IP247 traversing-program syntax errors (VP DB DW n+3; module error 48)\n    code_format: dec\n    defaults:\n      reaction: message\n      acknowledge: \"The program is rejected (not in the directory); correct it and write it again (BA22)\"\n      note: \"German original not preserved in the digest; English text only\"\n    entries:\n")
syn=[(0,'No error'),(1,'Text too long or <LF> missing'),(2,'Wrong block type or N missing'),(3,'Block number too large'),(4,'Subprogram number too large'),(5,'Function not allowed after G'),(6,'Function not allowed after X'),(8,'<LF> missing after the final block'),(9,'Block end: <LF> missing or wrong function present'),(10,'Path too large'),(11,'F value too large'),(12,'Too many decimal places'),(13,'Loop end missing'),(14,'Loop start missing'),(15,'Program end missing'),(16,'Unknown function'),(17,'M value too large'),(18,'New block after the final block'),(19,'Block too long'),(37,'G function not implemented')]
for v,t in syn:
    extra=', acknowledge: "Nothing to acknowledge"' if v==0 else ''
    o.append(f"      - {{code: {q(str(v))}, text: {q(t)}{extra}}}\n")
o.append("  - id: interface\n    title: IP247 interface error byte MB250 (handling blocks FB164/FB165)\n    code_format: hex1\n    defaults:\n      reaction: message\n      acknowledge: \"The job is not executed; correct the parameters and start it again (ANST 0→1)\"\n    entries:\n")
mb=[('0','No error'),('1','Error in the HTB PAFE byte (MB252/253)'),('2','Error in the module error byte (MB251)'),('5','Offset too large'),('6','Processing currently not possible'),('7','DB already exists'),('8','DB does not exist'),('9','Wrong ORG identifier'),('A','Target DB too small'),('B','Source DB too small'),('C','Source DB too large'),('D','Area in the AG too small'),('E','Area locked for I/O'),('F','Wrong acknowledgement')]
for c,t in mb:
    extra=', acknowledge: "Nothing to acknowledge"' if c=='0' else ''
    o.append(f"      - {{code: {q(c)}, text: {q(t)}{extra}}}\n")
open('/work/wt/profiles/profiles/devices/ip247/errors.yaml','w').write(''.join(o))
