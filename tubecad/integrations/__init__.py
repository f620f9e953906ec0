"""tubecad inside other tools: the OCP CAD Viewer and the CadQuery Workplane plugin."""
