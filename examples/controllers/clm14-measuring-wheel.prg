; CLM1.4 measuring wheel: two feeds of 100 IU; after each the motor position (V047) is kept in
; V600 / V601 and the axis position (V100: the sum of the wheel's moves in modes 3/4) in V602 / V603.
0000 PSI 1 +000100.000 999
0001 WAI 00.500
0002 SET V600 = V047
0003 SET V602 = V100
0004 PSI 1 +000100.000 999
0005 WAI 00.500
0006 SET V601 = V047
0007 SET V603 = V100
0008 JST 0008
