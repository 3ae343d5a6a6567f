; CLM1.4 Ax15 interrupt: the feed stops while I1.02.1 is missing, the next (non-feed) line runs
; meanwhile, and the feed completes once the signal is back, without Start.
0000 POI 1 +000100.000 999
0001 SET V601 = +1
0002 AKN Q1.00.2 1
0003 SET V600 = V100
0004 JST 0004
