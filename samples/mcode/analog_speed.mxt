` Analog speed control: the analog input sets the slew speed, input 3 stops.
` Shows registers, expressions, every comparison operator and conditional calls.

IS=5,9,0                ` analog input, 0-5 V
IS=3,0,0
D5=10                   ` filter the analog input
VM=768000
VI=1000

PG 100
LB A1
  R1=I5                 ` 0..4095
  R2=R1-2048
  R3=R2*100
  CL A2,R2<-50
  CL A3,R2>50
  CL A4,R2>=-50
  BR A5,I3=1
  BR A1,R1<>0
  BR A1,R1<=4095
LB A5
  SL 0
  H
  E

LB A2
  SL R3
  RT
LB A3
  SL R3
  RT
LB A4
  BR A6,R2>50
  SL 0
LB A6
  RT
PG
