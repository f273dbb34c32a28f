; Drilling a hole grid computed with variables.
; The grid origin, pitch and size live in V10-V15 so that a host can change
; them (ASCII Vn=...) before starting the program. Every assignment uses at
; most one operator, as the language requires. Rows are drilled in a
; serpentine order (odd rows right to left). Row number lamps on DO5-DO7.
; The drill cycle (spindle DO3, plunge on Z) is subroutine 3, after END.
ABS
HSPD=25000
LSPD=500
ACC=200
; origin X, origin Y, pitch X, pitch Y (pulses)
V10=2000
V11=1500
V12=3000
V13=2500
; columns, rows
V14=4
V15=3
; V20 = holes drilled, V16 = last column index
V20=0
V16=V14-1
V1=0
WHILE V1<V15
; Y of this row: V4 = origin Y + row * pitch Y
V3=V1*V13
V4=V3+V11
; row lamp: V8 = 16 << row  (DO5, DO6, DO7); keep the low nibble of DO
V7=16
V8=V7<<V1
V9=DO
V17=V9&15
V18=V17|V8
DO=V18
; V6 = 1 on odd rows
V6=V1%2
V2=0
WHILE V2<V14
; serpentine: on odd rows the column index runs backwards
IF V6=1
V5=V16-V2
ELSE
V5=V2
ENDIF
V19=V5*V12
V21=V19+V10
XV21YV4
WAITX
WAITY
GOSUB 3
V20=V20+1
V2=V2+1
ENDWHILE
V1=V1+1
ENDWHILE
; all lamps off, back to the origin
V22=~240
V23=DO
V24=V23&V22
DO=V24
X0Y0
WAITX
WAITY
; V25 = number of full rows drilled (for the host): holes / columns
V25=V20/V14
END
; SUB 3: drill one hole: spindle on, plunge 3000, dwell, retract, spindle off
SUB 3
DO3=1
DELAY=300
Z-3000
WAITZ
DELAY=100
Z0
WAITZ
DO3=0
ENDSUB
