; CLM1.4 AKP, vectors/clm14.md 25 (the pattern of `AKP M0.02 21001220` on the user input byte I1.02).
0000 AKP I1.02 21001220
0001 AEA Q1.00.0 1
0002 JST 0002
