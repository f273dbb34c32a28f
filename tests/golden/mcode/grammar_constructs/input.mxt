` every construct of grammars/mcode.lark, all valid
' apostrophe comment

VA Q1 = 4                 ` VA with spaces around =
VA Q2
NE=1                      ` a bare number repeats the last move
MA 1000
2000
-2000
!MR 512000                ` party prefixes: default, all, queued
*VM=500000
^MA 0
aPR P
Q2 = Q1 / 2 + 1 - 3 * 2   ` left to right: ((Q1/2)+1-3)*2
Q2=Q2&7|8^1
Q2=-Q1
Q2=!Q1
F1=CS F2
F3=PI*2
PR "Q2=",Q2;
PR "P=" P
PG 10
LB G1
  BR G1,I1=0
  BR G2,Q1<>0
  BR G2,Q1<=1
  BR G2,Q1>=2
  BR G2,Q1<3
  BR G2,Q1>4
  BR G2,AF&2
  CL K1,Q1=5
LB G2
  H
  E
LB K1
  RT
PG
