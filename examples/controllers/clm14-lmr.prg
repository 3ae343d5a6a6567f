; CLM1.4 LMR (manual §5.7 LMR; vectors/clm14.md 37) for examples/controllers/clm14-lmr.yaml:
; marks every 1000 IU, the cut 300 behind a mark. Part 1 with the light barrier 100 before the
; material entry (raster distance 900, offset distance 400), part 2 with it 100 after the entry
; (1100 / 200), part 3 before the entry again with no mark: the cut falls one mark distance
; after the previous one. BAC counts the parts.
0000 NOP
0001 LMR 1 001000.000 000300.000 +00100.000
0002 EOS
0003 LMR 1 001000.000 000300.000 -00100.000
0004 EOS
0005 LMR 1 001000.000 000300.000 +00100.000
0006 EOS
0007 JMP 0007
