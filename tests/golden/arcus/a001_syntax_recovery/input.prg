; three bad lines: each one diagnostic, the rest still checked
HSPD=1000
V1=(V2+1)
DELAY=
IF V1=1 X1000 ENDIF
V70=1
X1000
END
