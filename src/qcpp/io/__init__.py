"""File input and output for every package: output files whole or not at all (:mod:`qcpp.io.atomic`); native
output captured (:mod:`qcpp.io.capture`); child processes that die with their parent (:mod:`qcpp.io.children`);
the HTML tables reports show in a notebook (:mod:`qcpp.io.html`); progress lines and bars on stderr, the command
line's and the API's ``progress=True`` (:mod:`qcpp.io.progress`), and the width and wording they fit
(:mod:`qcpp.io.text`).

The lowest layer: it imports none of the project's packages, so the problem model (``qcpp.problem``), the compiler
(``qcpp``), the estimators, the simulators and the CLI all write files the same way.
"""
