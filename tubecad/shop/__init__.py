"""Shop-floor outputs (issue 13): cuttable web pieces nested on plates, flanges, bending
tables, marking lines, panel developments with their strain, and pin-jig tables."""
