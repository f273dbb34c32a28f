' Integer division of negative values. Outside the float registers F1-F8 MCode rounds a quotient
' down to the nearest integer (lexium-mcode.txt L1249): -7/2 is -4, 7/-2 is -4, -9/3 is -3.
VA N1=0
VA N2=0
VA N3=0
PG 100
LB MN
  N1=-7
  N2=N1/2
  PR N2
  N3=7
  N2=N3/-2
  PR N2
  N2=N1/-2
  PR N2
  N1=-9
  N2=N1/3
  PR N2
  E
PG
