; DXF-converter style: pen up / pen down subroutines never defined
HSPD=15000
LSPD=100
ACC=100
GOSUB 1
X0Y0
X13082Y17163
GOSUB 2
X13512Y20917
GOSUB 1
