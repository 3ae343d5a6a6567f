; CLM1.4 B018 error code output (vectors/clm14.md 39): a feed of axis 2 its drive cannot follow.
0000 AEA Q1.00.0 1
0001 POI 2 +000100.000 999
0002 JMP 0002
