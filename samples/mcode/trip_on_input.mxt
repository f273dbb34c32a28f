' Input trip: every rising edge on input 1 runs a short move profile.
' Shows trips (TI, TE), a handler that re-arms its trip before RT, and apostrophe comments.

VA Q1
D1=255                  ' debounce input 1

PG 1
LB G1
  TI 1,X1
  TE=1
LB G2
  Q1=0
  BR G2
  E

LB X1                   ' the trip handler
  IC Q1
  MR 51200
  H
  MR -51200
  H
  BR X1,Q1<4
  TE=1                  ' trips are one-shot: enable it again
  RT
PG
S
