"""Virtual devices: each dialect's host protocol with the state it exposes, served on a TCP port
(`mcc device`), so that downloads can be tried without hardware and tested over a real socket."""
