; CLM1.4 restart program 2 (manual §7.11, digest clm14.md §4.4): wait for I1.00.4 and 1 s, then
; restore everything.
0000 AEA Q1.00.3 1
0001 PSI 1 +000100.000 999
0002 JMP 0002
2000 AKN I1.00.4 1
2001 WAI 01.000
2002 RSV 1 0000 10000
