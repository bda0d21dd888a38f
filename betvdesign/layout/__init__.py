"""Layouts: a device file drawn as a GDS mask layout, and a GDS layout read back.

- :mod:`betvdesign.layout.convention`: how a layout names its elements and carries the
  device data it cannot draw (text labels on the process's annotation layer), the
  drawing's fixed choices, cell names;
- :mod:`betvdesign.layout.write`: ``betv layout``, a device file -> GDS (gdstk);
- :mod:`betvdesign.layout.shapes`: measuring drawn polygons (rectangles, discs, angles);
- :mod:`betvdesign.layout.drc`: the process's width, spacing and release rules on the
  drawn polygons;
- :mod:`betvdesign.layout.extract`: ``betv check FILE.gds`` and ``betv extract``, a GDS
  -> device file.

Above :mod:`betvdesign.checks` and :mod:`betvdesign.studies` (it reads and checks
specs), below :mod:`betvdesign.api` and what presents results (report, explore, cli).
Needs gdstk (``pip install 'betvdesign[layout]'``), imported when a layout is written or
read.
"""
