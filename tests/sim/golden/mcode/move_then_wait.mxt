' A move that the program does not wait for: output 1 goes on while the axis moves, H waits for
' the end of the move (lexium-mcode.txt L3048) before output 1 goes off; then a move waited for at
' once.
VI=1
VM=102400
A=1024000
D=1024000
PG 100
LB MN
  MR 51200
  O1=1
  H
  O1=0
  MR 25600
  H
  O2=1
  E
PG
