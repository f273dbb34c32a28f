; mcc: profile=pmx-2ed-sa
; Written for mcc's tests from the PMX-2ED-SA Manual Rev 1.18: two programs at once
; (p.42 §7.19, p.66 example 7), X and Y (p.5, p.62 X[pos]Y[pos]), EO per axis (p.26 Table 7.1).
PRG 0
HSPD=20000          ; p.61 HSPD
LSPD=500
ACC=500
DECX=400            ; p.60 DEC[axis]
EO=3                ; p.26: enable the X and Y motors
HOMEX-              ; p.61 HOME[axis][+/-]
WAITX
LHOMEY+             ; p.61 LHOME[axis][+/-]
WAITY
V63=0               ; p.44: V0-V63
WHILE V63<10
  X1000Y2000        ; p.62 linear interpolated move
  WAITX
  WAITY
  X0Y0
  WAITX
  WAITY
  V63=V63+1
ENDWHILE
GOSUB 1
END
PRG 1
TOC=5000            ; p.62 TOC
WHILE 1=1
  V1=AI1            ; p.60 AI[1-2]
  IF V1>2500
    STOPX           ; p.62 STOP[axis]
    SR0=0           ; p.61 SR[0-3]: stop program 0
  ENDIF
ENDWHILE
END
SUB 1
  DO1=1             ; p.60 DO[1-8]
  STORE             ; p.62 STORE
ENDSUB
SUB 31              ; p.43 §7.19.5: the error handler
  ECLEARX
  ECLEARY
ENDSUB
