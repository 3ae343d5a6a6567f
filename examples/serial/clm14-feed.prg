; hilbridge clm14 program
; CLM1.4 NC program: one instruction per line, "NNNN MNEMONIC operands" (fixed field widths as the device lists them)
; Feed 123456.789 mm at 12.3 % velocity, pulse Q1.00.3, wait, repeat (manual §5.7 / §9.2 examples).
0000 AEA Q1.00.3 1
0001 POI 1    +123456.789 123
0002 WAI 00.500
0003 AEA Q1.00.3 0
0004 BPA 0123 M2.02      21112212
0005 JMP 0000
