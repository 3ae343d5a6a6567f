; CLM1.4 manual §5.7 COU (digest clm14.md §4.4, vector 35): positions 10 times, then sets Q1.00.4
; and waits for Start.
0000 CLC 0002
0001 AEA Q1.00.4 0
0002 COU +00000 Q1.00.4 000010
0003 PSI 1 +000050.000 999
0004 WAI 01.000
0005 BCE 0001 Q1.00.4 0
0006 JST 0001
