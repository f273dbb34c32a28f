GOSUB 1 ;***Pen Up
X0Y0 ;***Go to start position
END
SUB 1
ENDSUB
