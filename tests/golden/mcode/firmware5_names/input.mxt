' An MDrive program for firmware before 6: AB, LO and SQ are plain names there
' (profile.toml targets firmware 5.0); on firmware 6 they are math functions.
VA LO=12200
VA SQ=0
PG 100
LB AB
  MA LO
  H
  SQ=SQ+1
  CL AB,SQ<5
  E
PG
