' Subroutine calls: SB pulses output 2; the main program moves and calls it three times.
VA N1=0
VI=500
VM=5000
A=50000
D=50000
PG 100
LB MN
  MR 1000
  H
  CL SB
  IC N1
  BR MN,N1<3
  E
LB SB
  O2=1
  H 100
  O2=0
  RT
PG
