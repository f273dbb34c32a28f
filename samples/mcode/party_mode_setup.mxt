` Two drives on one RS-485 bus in party mode: commands addressed by device name.
` These lines run immediately while the file is downloaded (no program).

*VM=500000              ` every drive: maximum velocity
aMR 51200               ` drive a: one revolution forward
bMR -51200              ` drive b: one revolution back
aPR P
bPR P
