; CLM1.4 manual §5.7 CIO/CVT, Fig. 5-10 (digest clm14.md §4.4): read a 4-decade BCD switch into
; V600. Q1.01.0..3 select the decade (units first), its digit is read from I1.01.0..3 20 ms later
; into the BCD field M2.00..M2.07 (integer digits from M2.03), then CVT converts the field.
0000 APE Q1.01 22220001
0001 WAI 00.02
0002 CIO I1.01.0 M2.03.0 04
0003 APE Q1.01 22220010
0004 WAI 00.02
0005 CIO I1.01.0 M2.03.4 04
0006 APE Q1.01 22220100
0007 WAI 00.02
0008 CIO I1.01.0 M2.04.0 04
0009 APE Q1.01 22221000
0010 WAI 00.02
0011 CIO I1.01.0 M2.04.4 04
0012 CVT V600 M2.00 0 1
0013 JST 0000
