' True mistakes in an MDrivePlus program, each reported: a function S1-S4 do not have (9, M108),
' an active level of 2 (M108), a three-letter name (the family's names are one or two
' characters, M103), a write to the analog input, which can only be read (M107).
S1=9,0,0
S2=0,2,0
VA ABC=1
VA TH=1023
PG 100
LB K1
 BR K1, I5<TH
 I5=1024
 E
PG
