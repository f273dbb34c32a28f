; Subroutine calls: SUB 1 pulses output 2; the main program moves and calls it three times.
INC
HSPD=5000
LSPD=500
ACC=100
V1=0
WHILE V1<3
X1000
WAITX
GOSUB 1
V1=V1+1
ENDWHILE
END
SUB 1
DO2=1
DELAY=100
DO2=0
ENDSUB
