VA Q1
PG 100
LB AA
  PR "rev 1"
  E
' the TB routine: trust the brake
#include "../brake.mxt"
#if HOMING == "end"
LB M1
  HM 3
  H
  TT = 100, TB
  E
#else
LB M1
  E
#endif
PG
S
' end
