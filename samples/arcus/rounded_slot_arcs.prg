; Arc and circle moves: a pen plotter draws a 20000 x 10000 rectangle with
; rounded corners (radius 2000), then a clockwise circle of radius 1500 and a
; counter-clockwise circle of radius 1000 about the centre of the rectangle.
; Pen down = DO4 on. Arcs and circles use the X and Y axes, absolute centres.
; ARC angles are in 1/1000 degree, measured from the -X axis about the centre;
; mcc reads the angle as the absolute end angle measured clockwise from -X
; (spec 7.5, to be verified on hardware). ARCP = clockwise, ARCN = counter-clockwise.
ABS
HSPD=12000
LSPD=300
ACC=150
DO4=0
; start of the outline: left edge, bottom end of the straight part
X0Y2000
WAITX
WAITY
DO4=1
; left edge up
Y8000
WAITY
; top-left corner: centre (2000,8000), end on +Y of the centre = 90 degrees
ARCP2000:8000:90000
WAITX
WAITY
; top edge
X18000
WAITX
; top-right corner: centre (18000,8000), end on +X of the centre = 180 degrees
ARCP18000:8000:180000
WAITX
WAITY
; right edge down
Y2000
WAITY
; bottom-right corner: centre (18000,2000), end on -Y of the centre = 270 degrees
ARCP18000:2000:270000
WAITX
WAITY
; bottom edge
X2000
WAITX
; bottom-left corner: centre (2000,2000), end on -X of the centre = 360 degrees
ARCP2000:2000:360000
WAITX
WAITY
DO4=0
; circles about the middle (10000,5000), starting 1500 to the left of it
X8500Y5000
WAITX
WAITY
DO4=1
CIRP10000:5000
WAITX
WAITY
DO4=0
; a second, counter-clockwise circle of radius 1000 about the same centre
X9000
WAITX
DO4=1
CIRN10000:5000
WAITX
WAITY
DO4=0
X0Y0
WAITX
WAITY
END
