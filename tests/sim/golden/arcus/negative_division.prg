; Integer division of negative values. The manual does not say how a quotient rounds; the project
; truncates toward zero, as C does (arcus-spec.md section 2.4, docs/SIMULATOR.md "Variables and
; arithmetic"): -7/2 is -3, 7/-2 is -3, -9/3 is -3. Outputs 1, 2 and 3 go on.
V1=-7
V2=V1/2
IF V2=-3
DO1=1
ENDIF
V3=7
V2=V3/-2
IF V2=-3
DO2=1
ENDIF
V1=-9
V2=V1/3
IF V2=-3
DO3=1
ENDIF
END
