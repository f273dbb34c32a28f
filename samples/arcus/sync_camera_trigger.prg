; Position-compare (sync output) example.
; A camera on DO1 must fire a 5 ms pulse each time the X axis passes one of
; four inspection points 5000 counts apart. The X sync output (wired to DO1)
; fires when the X ENCODER position equals SYNXP (condition 1, width SYNXT).
; While X is moving, the Y sync output (DO2) is used as a "zone" signal with
; condition 3: on while the Y encoder is below 2000.
; A 3 s timeout (TR) guards every trigger; a missed trigger lights DO8.
; Assumes the encoder counts 1:1 with the pulses (4X decoding).
; DO1/DO2 are never written while their sync output is on.
ABS
HSPD=8000
LSPD=200
ACC=150
PX=0
EX=0
DO8=0
; Y zone signal: DO2 on while the Y encoder is below 2000
SYNYC=3
SYNYP=2000
SYNYO
; V1 = next trigger position, V2 = points done
V1=5000
V2=0
WHILE V2<4
SYNXC=1
SYNXP=V1
SYNXT=5
SYNXO
; move 1000 counts past the trigger point
V3=V1+1000
XV3
; wait for the trigger or the timeout: V5 = 0 waiting, 1 fired, 2 timeout
TR=3000
V5=0
WHILE V5=0
V4=SYNXS
IF V4=2
V5=1
ENDIF
IF TR=0
V5=2
ENDIF
ENDWHILE
SYNXF
WAITX
IF V5=2
DO8=1
ENDIF
V1=V1+5000
V2=V2+1
ENDWHILE
SYNYF
X0
WAITX
END
