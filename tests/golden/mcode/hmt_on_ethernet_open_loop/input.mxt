' hMTechnology on the Ethernet model without hMT (profile lmd-e): every set and read is Error 37
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
