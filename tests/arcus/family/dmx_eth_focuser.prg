; mcc: profile=dmx-eth
; Written for mcc's tests in the shape of real DMX-ETH programs (host-called subroutines, status
; in variables up to V100, EO around each move) and with the ACE-SDE statements the DMX-ETH
; shares (docs/dialects/arcus.md, "Family").
PRG 0
V33=20240101
V44=0
END
SUB 29              ; go to the target in V20
  V46=1
  V1=V20
  IF V1<=0
    V46=172
    SR0=0
  ENDIF
  ABS
  EO=1              ; enable the motor driver
  HSPD=10000
  LSPD=500
  V10=10*V1
  XV10
  WAITX
  EO=0              ; disable it again
  V46=0
ENDSUB
SUB 30              ; home on the index
  EO=1
  JOGX-
  WAITX
  ECLEARX
  V11=MSTX
  V5=V11&16
  WHILE V5>0
    ZOMEX+
    WAITX
    V11=MSTX
    V5=V11&16
  ENDWHILE
  V44=V100
  EO=0
ENDSUB
SUB 31
  ECLEARX
ENDSUB
