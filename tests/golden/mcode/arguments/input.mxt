VA Q1
MA
MA 1,2,3,4
MA "home"
IS=1,0
BR 12.5
R1=R2!R3
PR "Position: " P
VR
P
PG1
E
PG
