; CLM1.4 flying cutoff program for examples/controllers/clm14-flying-cutoff.yaml: five parts of
; 100 IU. LML arms the carriage's sync on master encoder 1 so that the cut falls 100 IU of
; material after the last one; once synchronous the knife (Q1.00.0) goes down for 0.1 s, FUN
; buffers the material that passed the tool since the last cut in V025, CPS sets Q1.00.1 when that
; part is 100.000 +/- 0.01 IU; EOS sends the carriage home at Vmax. BAC counts the parts.
0000 NOP
0001 LML 1 000100.000
0002 AEA Q1.00.0 1
0003 FUN 2222220
0004 CPS V025 = +000100.000 0000.01 Q1.00.1
0005 WAI 00.100
0006 AEA Q1.00.0 0
0007 AEA Q1.00.1 0
0008 EOS
0009 BAC 0001 +0000 00005
0010 JMP 0010
