; CLM1.4 HOM, option 1 (manual §7.9): to the cam, off it at V1/4, back to the first encoder
; marker behind the cam edge, crept back onto it: that marker is Ax25 = +5. V600 keeps the
; position just after homing; PSA +50 then moves to CLM 50.
0000 HOM 1
0001 AKN Q1.00.1 1
0002 SET V600 = V100
0003 PSA 1 +000050.000 999
0004 JST 0004
