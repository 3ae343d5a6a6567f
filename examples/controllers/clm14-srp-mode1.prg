; CLM1.4 SRP mode 1 (manual §5.7 SRP, Fig. 5-29) for examples/controllers/clm14-srp-mode1.yaml:
; desired distance from the print mark to the end of the feed V601 = 20, maximum correction
; V602 = 10, no search window (V604 = 0). Every PSI measures; the correction (V601 - V600, limited
; to V602) is added to the next feed. The processing subroutine pulses the knife Q1.00.0; BAC
; stops after three feeds.
0000 SET V601 = +20.0
0001 SET V602 = +10.0
0002 SET V604 = +0.0
0003 SRP 1 1 0 V600 M2.02
0004 WAI 00.100
0005 PSI 1 +000100.000 999
0006 JSR 0100
0007 BAC 0005 +0000 00003
0008 JMP 0008
0100 AEA Q1.00.0 1
0101 WAI 00.100
0102 AEA Q1.00.0 0
0103 RTS
