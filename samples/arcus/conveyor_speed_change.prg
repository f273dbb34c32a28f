; Conveyor with on-the-fly speed changes on the U axis.
; The conveyor jogs continuously; a selector switch picks its speed:
; DI4 = fast (40000 pps), DI5 = slow (8000 pps), neither = normal (20000 pps).
; SSPD changes the speed while moving. It needs a trapezoidal profile
; (SCVU=0) and a speed window: SSPDMU=2 covers 2..130000 pps.
; DI6 stops the conveyor. The current pulse speed is copied to V3 for a host.
; The per-axis U speeds are used because HSPDU, LSPDU and ACCU are all set.
SCVU=0
HSPDU=20000
LSPDU=200
ACCU=500
SSPDMU=2
; clear a limit/alarm error left from a previous run
ECLEARU
JOGU+
; V1 = current speed, V2 = requested speed, V9 = 1 when stopping
V1=20000
V9=0
WHILE V9=0
IF DI4=1
V2=40000
ELSEIF DI5=1
V2=8000
ELSE
V2=20000
ENDIF
IF V2!=V1
SSPDU=V2
V1=V2
ENDIF
V3=PSU
IF DI6=1
V9=1
ENDIF
DELAY=50
ENDWHILE
STOPU
WAITU
; back to normal operation: the speed window must be reset to 0
SSPDMU=0
END
