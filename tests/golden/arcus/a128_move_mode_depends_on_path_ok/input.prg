; The same program with the mode written where each move needs it.
HSPD=5000
V1=0
WHILE V1<3
ABS
X1000
INC
X10
V1=V1+1
ENDWHILE
GOSUB 1
ABS
GOSUB 1
END
SUB 1
INC
Y500
ENDSUB
