' IC/DC: user variables and counters step; modes and configuration are Error 26 (M140)
VA Q1=0
PG 1
LB K1
  IC Q1
  DC R2
  IC P
  IC MS
  DC EE
  IC BD
  IC MV
  E
PG
