; Arithmetic at the 32-bit limits. The manual states no range; the project takes variables and
; literals as signed 32-bit integers that wrap in two's complement (arcus-spec.md section 2.4,
; docs/SIMULATOR.md "Variables and arithmetic"), and a literal must fit (A119). So 2147483647 + 1
; is -2147483648, -2147483647 - 2 is 2147483647 and 65536 * 65536 is 0: outputs 1 and 3 go
; on, output 2 stays off.
V1=2147483647
V2=V1+1
IF V2<0
DO1=1
ENDIF
V3=-2147483647
V4=V3-2
IF V4<0
DO2=1
ENDIF
V5=65536
V6=V5*65536
IF V6=0
DO3=1
ENDIF
END
