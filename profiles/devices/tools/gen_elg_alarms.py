import re, json
src=open('/work/shared/seeds/sinumerik-elg.md').read()
def q(s): return json.dumps(s, ensure_ascii=False)
def section(a,b): return src[src.index(a):src.index(b)]
def rows(sec):
    out=[]
    for line in sec.splitlines():
        if not line.startswith('| ') or line.startswith('|---') or line.startswith('| No. |'): continue
        out.append([c.strip() for c in line.strip()[1:-1].split(' | ')])
    return out
def clean(s): return s.replace('**','').replace('\\*','*')
RESET="RESET (ELG-RESET interface signal, wired to the NC Reset key) with the gearing disengaged, or POWER ON RESET"
POWER="POWER ON RESET only"
o=["# SPDX-License-Identifier: MIT\n# SINUMERIK ELG alarms (ch. 11, 12.3). Power-on alarms < 100, reset alarms from 100* up;\n# 104* etc. are per axis (number = base + axis index 0…3). The manual is English (text_de empty).\n# Reaction classes: the manual's 'STOP' bundle (set value 0, ELG-BB2 dropped, controller enable\n# released after MD 156, follow-up) = drive_off. Part of sinumerik-elg.yaml.\ndevice: sinumerik-elg\ncatalogues:\n  - id: alarms\n    title: ELG alarms (ALARM nnnn on the VDU; E65.5 'ELG alarm')\n    code_format: dec\n    defaults:\n      acknowledge: "+q(RESET)+"\n    entries:\n"]
react={1:'drive_off',2:'drive_off',3:'drive_off',4:'message',8:'drive_off',19:'stop',22:'stop',
       104:'message',108:'drive_off',112:'drive_off',116:'drive_off',132:'needs_reset',136:'message',156:'drive_off',160:'message',168:'drive_off',184:'stop',
       2000:'drive_off',2035:'stop',2200:'needs_reset',2201:'stop',2202:'stop',2203:'stop',2204:'stop',2205:'stop',2206:'message',2207:'stop',2214:'message',2215:'drive_off',3016:'message',3018:'message'}
for sec,group in [(section('### 10.1 Power-on alarms','### 10.2'),'power-on alarm'),(section('### 10.2 Reset alarms, axis-specific','### 10.3'),'reset alarm, axis {axis}'),(section('### 10.3 Reset alarms, general and ELG','## 11.'),'reset alarm')]:
    for c in rows(sec):
        c=(c+['']*7)[:7]
        no,text,when,effect,cause,remedy,bb2=[clean(x) for x in c]
        star=no.endswith('*')
        base=int(no.rstrip('*'))
        r=react.get(base,'stop')
        ack=RESET
        if base in (132,2200): ack=POWER
        if base==3016 or base==3018: ack="Nothing to acknowledge: the transfer is refused but acknowledged; correct the PC program"
        if base==2204:
            text="(no text in the manual; referenced by alarm 2207 as 'alarm message 2204 is present')"
        note=[]
        if when: note.append('checked: '+when)
        if effect: note.append('effect: '+effect)
        if bb2=='X': note.append('drops ELG READY 2 (BB2)')
        if base==2: note.append('drops ELG READY 1 (BB1)')
        notes='; '.join(note)
        if star:
            codes=', '.join(str(base*10+i) for i in range(4))
            o.append(f"      - {{series: [{codes}], text: {q(text)}, group: {q(group)}, cause: {q(cause)}, remedy: {q(remedy)}, reaction: {r}, acknowledge: {q(ack)}, note: {q(notes)}}}\n")
        else:
            o.append(f"      - {{code: {q(str(base))}, text: {q(text)}, group: {q(group.replace(', axis {axis}',''))}, cause: {q(cause)}, remedy: {q(remedy)}, reaction: {r}, acknowledge: {q(ack)}, note: {q(notes)}}}\n")
open('/work/wt/profiles/profiles/devices/sinumerik-elg/alarms.yaml','w').write(''.join(o))
