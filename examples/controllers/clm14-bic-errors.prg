; CLM1.4 BIC errors (manual §5.7 BIC): a BCD digit above 9 is error 0D, a target past 2999 is 0E.
; M3 markers are retentive: the second start (after Clear) takes the second case.
0000 BCE 0010 M3.00.0 1
0001 AEA M3.00.0 1
0002 APE M2.02 22221010
0003 BIC 0500 11 M2.02.0 4 1
0004 JST 0004
0010 AEA M3.00.0 0
0011 APE M2.02 22222221
0012 BIC 2999 1 M2.02.0 1 0
0013 JST 0013
