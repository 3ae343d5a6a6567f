; CLM1.4 master encoder 2: VEO source 6 takes axis 1's override from its velocity [decided, as
; source 5 from master encoder 1]; FUN's sixth digit measures its travel in V042 / V043.
0000 FUN 2222202
0001 VEO 1 6 1 000 0
0002 POI 1 +000100.000 999
0003 WAI 01.000
0004 SET V600 = V104
0005 AKN I1.00.0 1
0006 FUN 2222202
0007 JST 0007
