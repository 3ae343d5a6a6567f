; CLM1.4 B017 analog override (AE1 on axis 1): a 400 IU feed at 999 per mille (99.9 IU/s) whose
; velocity follows the voltage on AE1; the program samples the actual velocity V104 and the
; normalised input V007 while the scenario turns the potentiometer.
0000 POI 1 +000400.000 999
0001 WAI 01.000
0002 SET V600 = V104
0003 WAI 01.200
0004 SET V601 = V104
0005 SET V602 = V007
0006 WAI 02.200
0007 SET V603 = V104
0008 SET V604 = V007
0009 AKN Q1.00.2 1
0010 JST 0010
