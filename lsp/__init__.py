"""mcc's language server (`mcc lsp`): the compiler's checks and knowledge of each dialect in an editor.

Installed with the optional extra `mcc[lsp]` (pygls 2). See docs/EDITORS.md.
"""
