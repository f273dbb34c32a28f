; A loop that switches to INC after its first move: the first move is absolute on the first pass
; and incremental on the next ones, and a subroutine called in both modes.
HSPD=5000
ABS
V1=0
WHILE V1<3
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
Y500
ENDSUB
