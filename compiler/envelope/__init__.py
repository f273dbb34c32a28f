"""The machine's envelope (issue 27): where each axis may go and how fast its mechanics allow.

- `axes`: the `[tool.mcc.axes.<axis>]` configuration (and a profile's `[envelope.<axis>]`), in steps;
- `intervals`: an abstract interpretation of a module over intervals, which the lint rules of
  `compiler/lint/rules/envelope/` read to prove a program keeps its axes inside their travel.

The simulator's travel stop and cycle times are in `sim/` (docs/SIMULATOR.md, "Envelope").
"""
