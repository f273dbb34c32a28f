' Written for mcc after the sample program of the application note "Converting MDrive MCode to
' Lexium MCode" (motion.schneider-electric.com/application-note/converting-mdrive-mcode-lexium-mcode/):
' input 1 starts a slew at a multiple of the 10-bit analog input, I/O point 2 is a moving output,
' the program runs at power-up (LB SU). S1=0,1 gives function and active level only.
S1=0,1
S2=17,1,0
VA K1=20
PG 1
LB SU
LB K2
 BR K2, I1=0
 R1=I5*K1
 SL R1
 H 1000
 SL 0
 H
 BR K2
PG
