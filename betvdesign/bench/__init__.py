"""Speed against accuracy (issue 6): the work-precision study (:mod:`.workprecision`,
:mod:`.chart`), a fixed-step comparison integrator (:mod:`.fixedstep`), the failure map
as data (:mod:`.failures`) and along ϖ (:mod:`.failuremap`), and the measurements behind
the fidelity ladder (:mod:`.ladder`). ``betv bench``, ``betv ladder`` and
``betv report --methods`` are the command-line entry points.
"""
