"""`mcc debug`: a Debug Adapter Protocol server that runs a program on the simulator.

protocol.py frames the messages (Content-Length headers and JSON), conditions.py evaluates
breakpoint conditions and watch expressions, session.py runs the simulator step by step in a
thread of its own, server.py answers the requests. docs/EDITORS.md, "Debugging", shows a session.
"""
