; mcc: profile=ace-sde
; Written for mcc's tests from the ACE-SDE Manual Rev 1.24: one axis X (p.5), V1-V100 (p.49),
; two programs (p.47, p.79 example 7), the latch (p.41), the driver settings (p.72, p.74).
PRG 0
DRVRC=1000          ; p.72 DRVRC
DRVMS=100           ; p.72 DRVMS
RW                  ; p.74 RW: write the driver settings, then wait 2 s
DELAY=2000
HSPD=20000
LSPD=1000
ACC=300
EO=1                ; p.73: "EO=1 ;Enable the motor"
ZHOMEX+             ; p.75 ZHOMEX[+/-]
WAITX
LTX=1               ; p.73 LTX: arm the latch
V100=0
WHILE V100<3
  X10000
  WAITX
  V99=LTSX          ; p.73 LTSX
  IF V99=2
    V98=LTPX        ; p.73 LTPX
  ENDIF
  X0
  WAITX
  V100=V100+1
ENDWHILE
EO=0
END
PRG 1
WHILE 1=1
  IF DI6=0          ; p.40 Table 6.2: DI1-DI6
    ABORTX          ; p.72 ABORTX
    SR0=0           ; p.74 SR[0-1]
  ENDIF
ENDWHILE
END
SUB 31
  ECLEARX
ENDSUB
