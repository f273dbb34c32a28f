; Sorting station: a diverter arm on the X axis sends each part to one of four
; bins according to a 2-bit part code on DI2/DI3, read when the part-present
; sensor DI1 triggers. A pusher on DO2 ejects the part.
; Shows WHILE, IF/ELSEIF/ELSE, a bit mask on the whole input byte, and
; subroutines (GOSUB) defined after END.
;   code 1 (DI2 only)   -> bin at X=5000
;   code 2 (DI3 only)   -> bin at X=10000
;   code 3 (DI2 + DI3)  -> bin at X=15000
;   no code             -> reject bin at X=20000
; Runs 50 parts; V5 counts rejects for the host.
ABS
HSPD=20000
LSPD=400
ACC=200
DO=0
GOSUB 1
V3=0
V5=0
WHILE V3<50
WHILE DI1=0
DELAY=5
ENDWHILE
; DI byte: bit 0 = DI1, bit 1 = DI2, bit 2 = DI3; keep bits 1 and 2
V1=DI
V2=V1&6
IF V2=2
V4=5000
ELSEIF V2=4
V4=10000
ELSEIF V2=6
V4=15000
ELSE
V4=20000
V5=V5+1
ENDIF
XV4
WAITX
GOSUB 2
GOSUB 1
V3=V3+1
ENDWHILE
END
; SUB 1: bring the diverter arm back to its rest position
SUB 1
X0
WAITX
ENDSUB
; SUB 2: fire the pusher for 300 ms, then wait for it to retract
SUB 2
DO2=1
DELAY=300
DO2=0
DELAY=200
ENDSUB
