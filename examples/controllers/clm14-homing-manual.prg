; CLM1.4: homing from the Ax23 input in Manual needs no program (clm14-homing-manual.yaml).
0000 NOP
