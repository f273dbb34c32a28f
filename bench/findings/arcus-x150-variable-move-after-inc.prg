; bench/fuzz_codegen.py finding (arcus seed 258, all features, minimized): PROBABLY KNOWN (issue 23, X150
; writer: a move to a variable after a mode switch; the generator feature moves_var is left out of the
; bounded test for it). mcc compile --target x150: S010 - the source moves X to -3000 (ABS at power-up)
; and then, with input 3 low, INC by V3=-1000 to -4000; the X150 output goes elsewhere.
IF V1=9
ENDIF
WHILE V5<2
IF V2=4
ENDIF
V5=V5+1
ENDWHILE
V3=-3000
XV3
IF DI3=0
V3=-1000
INC
XV3
WHILE V5<1
ENDWHILE
ENDIF
