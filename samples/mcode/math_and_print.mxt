` Floating point math and print formatting (firmware 6.0.01+).
` Shows F registers, functions, PI, RA, PF, PR without a line end, bitwise operators.

RA=1                    ` angles in radians
PF=10,4,0,0             ` print F registers with 4 decimals

PG 200
LB M1
  F1=PI
  F2=F1/4
  F3=SI F2
  F4=CS F2
  F5=SQ 2
  F6=AB -12
  PR "sin(pi/4) = ";
  PR F3
  PR "cos(pi/4) = ",F4
  R1=12
  R2=R1&10
  R3=R1|3
  R4=R1^5
  R1=!R4
  PR R1,R2,R3,R4
  E
PG
