; CLM1.4 HOM against a badly placed cam (manual §7.9): error 4B "Mrkr Pulse Pos A1".
0000 HOM 1
0001 AKN Q1.00.1 1
0002 AEA Q1.00.4 1
0003 JST 0003
