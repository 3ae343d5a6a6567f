; CLM1.4 manual §5.7 BAC (digest clm14.md §4.4): counting after the event, positions 10 times.
0000 WAI 01.000
0001 PSI 1 +000050.000 250
0002 BAC 0000 +0000 00010
0003 JST 0000
