"""The command line: one module per command, shared option blocks and display helpers."""
