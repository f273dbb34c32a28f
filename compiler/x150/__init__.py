"""The Parker/Digiplan X150/X150E dialect (docs/dialects/x150.md).

Frontend: parser (grammars/x150.lark cuts lines into command tokens) → tokens (each token read
against the catalog) → structure (sequence definitions and immediate stretches) → lower (IR) →
checks. Backend side, IR only: structurer (constructs from the CFG) → writer (canonical text),
wrapped by mcc.backends.x150. Shared: catalog, naming.
"""
