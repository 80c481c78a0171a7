"""The ``svgtile`` command line: one module per command, registered onto one group."""
