; A loop on an input: shuttle X between 0 and 2000 until input 2 is on, counting the trips.
ABS
HSPD=8000
LSPD=400
ACC=100
V1=0
WHILE DI2=0
X2000
WAITX
X0
WAITX
V1=V1+1
ENDWHILE
DO1=1
END
