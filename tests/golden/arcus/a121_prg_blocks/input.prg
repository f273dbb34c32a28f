; mcc: profile=pmx-4ex-sa
PRG 0
X1000
END
PRG 1
Y1000
END
