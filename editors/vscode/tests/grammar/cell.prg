; SYNTAX TEST "source.arcus" "control, subroutines, variables, moves"
WHILE DI2=0
; <- keyword.control.arcus
;     ^^ support.function.arcus
;        ^ keyword.operator.arcus
X12000Y4000
; <- support.function.arcus
;^^^^^ constant.numeric.arcus
;     ^ support.function.arcus
GOSUB 1
; <- keyword.control.arcus
;     ^ entity.name.function.arcus
V1=V1+1 ; count
; <- variable.other.arcus
;  ^^ variable.other.arcus
;       ^^^^^^^ comment.line.semicolon.arcus
ENDWHILE
; <- keyword.control.arcus
