"""Benchmarks: accuracy-vs-cost, throughput and controller comparisons (CSV + PNG).

Each command is a package whose modules are discovered: a module `benchmarks/<kind>/<name>.py`
contributes a scene by defining the functions the package's `__init__` documents. Adding a scene
needs no edit of a shared list.
"""
