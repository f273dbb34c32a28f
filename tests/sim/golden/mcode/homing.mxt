' Homing: home to the switch (HM 1), then index to 4000 and switch output 1 on.
IS=1,1,0
VI=400
VM=4000
A=20000
D=20000
PG 100
LB HO
  HM 1
  H
  MA 4000
  H
  O1=1
  E
PG
