; CLM1.4 manual §5.7 BAC (digest clm14.md §4.4): counting before the event, positions 9 times.
0000 BAC 0002 +0000 00010
0001 JST 0000
0002 PSI 1 +000050.000 250
0003 WAI 01.000
0004 JMP 0000
