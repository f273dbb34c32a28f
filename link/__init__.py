"""The device link: download, verify, upload and a terminal over serial or TCP (docs/LINK.md).

pyserial is an optional dependency (`pip install "mcc[link]"`); it is imported only when a port
is opened, so the rest of mcc works without it.
"""
