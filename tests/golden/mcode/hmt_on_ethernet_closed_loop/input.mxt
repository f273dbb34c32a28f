' hMTechnology on the closed-loop Ethernet model (LMDCE, profile lmd-ce): set and read
AS=1
LD=100
PG 1
LB K1
  BR K2,LR=1
  R1=AV
  PR AF
  E
LB K2
  CF
  E
PG
