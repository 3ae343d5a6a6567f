; CLM1.4 flying cutoff functions for examples/controllers/clm14-cutoff-functions.yaml: parts of
; 100 IU (LML); in sync the knife (Q1.00.0) is down for 1 s, EOS returns the carriage, COU counts
; the finished parts on M3.00.0's counter. The rapid-stop program (A136 -> 0200) marks M3.00.1 and
; ends with EOS: the CLM then stops with error 3B.
0000 NOP
0001 LML 1 000100.000
0002 AEA Q1.00.0 1
0003 WAI 01.000
0004 AEA Q1.00.0 0
0005 EOS
0006 COU +00000 M3.00.0 000099
0007 JMP 0001
0200 AEA M3.00.1 1
0201 WAI 00.050
0202 EOS
