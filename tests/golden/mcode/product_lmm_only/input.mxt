` SA and EL exist only on the Lexium Motion Module; the default profile is an LMD
SA=1.8
EL=500
A=20000
