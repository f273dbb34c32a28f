' The same names on firmware 6 (the default profile): each is reported once, naming the firmware.
VA LO=12200
VA SQ=0
PG 100
LB AB
  MA LO
  H
  R1=AB
  F1=AB P
  F2=SQ AB R2
  R3=XY R2
  E
PG
