; CLM1.4 manual vector (manual §7.10, digest clm14.md §4.4): 0400..0402 switch Q1.00.0 and Q1.00.1
; off; the main program sets them in Automatic.
0000 AEA Q1.00.0 1
0001 AEA Q1.00.1 1
0002 JST 0002
0400 AEA Q1.00.0 0
0401 AEA Q1.00.1 0
0402 RTS
