; CLM1.4 B017 override inputs and the Ax32 outputs: a 200 IU feed at 999 per mille under the
; Gray-code override; V600 takes the actual velocity (V104) in the middle of the feed.
0000 POI 1 +000200.000 999
0001 WAI 01.000
0002 SET V600 = V104
0003 AKN Q1.00.2 1
0004 JST 0004
