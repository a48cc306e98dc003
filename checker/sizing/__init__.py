"""``checker new``: a first crank-train layout from a concept brief, written as a workbook.

:mod:`checker.sizing.brief` reads the brief; :mod:`checker.calc.first_layout` holds the design
rules and their sources; :mod:`checker.sizing.new_engine` sizes the layout and writes every
sheet of the workbook, each derived value's note naming its rule and source and marked
``ESTIMATE`` (distinct from the user's ``ASSUMPTION`` and from typed data).
"""
