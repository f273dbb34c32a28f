' A loop on an input: shuttle between 0 and 2000 until input 2 is on, counting the trips.
VA N1=0
VI=400
VM=8000
A=80000
D=80000
PG 100
LB LP
  MA 2000
  H
  MA 0
  H
  IC N1
  BR LP,I2=0
  O1=1
  E
PG
