; CLM1.4 multitasking (manual §7.5, digest clm14.md §4.4): task 2 counts I1.00.0 pulses and sets
; Q1.00.7 at the 10th; task 3 mirrors I1.00.1 to Q1.00.6 in every mode.
0000 JMP 0000
0200 AKN I1.00.0 1
0201 AKN I1.00.0 0
0202 COU +00000 Q1.00.7 000010
0203 JMP 0200
0800 BCE 0803 I1.00.1 1
0801 AEA Q1.00.6 0
0802 JMP 0800
0803 AEA Q1.00.6 1
0804 JMP 0800
