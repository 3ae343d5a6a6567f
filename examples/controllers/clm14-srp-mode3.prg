; CLM1.4 SRP mode 3 (manual §5.7 SRP, Fig. 5-30) for examples/controllers/clm14-srp-mode3.yaml:
; SRP only measures (V600, M2.02.4); the program corrects the next feed itself: when a mark was
; seen, the feed V701 = V700 + (V601 - V600), else the nominal V700 = 100. BAC stops after three
; feeds; the processing subroutine pulses the knife Q1.00.0.
0000 SET V601 = +20.0
0001 SET V602 = +10.0
0002 SET V604 = +0.0
0003 SET V700 = +100.0
0004 SET V701 = +V700
0005 SET V702 = +0.0
0006 SRP 1 3 0 V600 M2.02
0007 WAI 00.100
0008 PSI 1 V701 999
0009 BCE 0012 M2.02.4 1
0010 SET V701 = +V700
0011 JMP 0014
0012 MAT V702 = V601 - +V600
0013 MAT V701 = V700 + +V702
0014 JSR 0100
0015 BAC 0008 +0000 00003
0016 JMP 0016
0100 AEA Q1.00.0 1
0101 WAI 00.100
0102 AEA Q1.00.0 0
0103 RTS
