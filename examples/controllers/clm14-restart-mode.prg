; CLM1.4 restart program 1 (manual §7.11, digest clm14.md §4.4): restore everything at once.
0000 AEA Q1.00.3 1
0001 PSI 1 +000100.000 999
0002 JMP 0002
2000 RSV 1 0000 10000
