"""Outputs: pictures now; STEP, IGES and BREP files as the B-rep stage lands."""
