` Pick and place: wait for a part, move over it, grip, place it, count it.
` Target: Lexium MDrive closed loop (profile lmd-c).

`[VARIABLES]
VA Np=0                 ` parts placed
VA Pp=512000            ` pick position, 10 revolutions

` I/O: input 1 = part present, input 2 = home switch, output 1 = gripper
IS=1,0,1
IS=2,1,0
OS=1,16,1
MS=256
VI=2000
VM=400000
A=800000
D=A
RC=75
HC=20

`[PROGRAMS]
PG 1
LB SU                   ` runs at power-up
  HM 1                  ` home on input 2
  H
  P=0
LB G1
  BR G1,I1=0            ` wait for a part
  CL K1
  IC Np
  PR "Parts placed: ",Np
  BR G1
  E

`[SUBROUTINES]
LB K1                   ` pick the part at Pp, place it at 0
  MA Pp
  H
  O1=1                  ` close the gripper
  H 250
  MA 0
  H
  O1=0
  H 250
  RT
PG
S
` Keep this line to save the program on load
