"""Outputs: CAD files (cad), meshes (mesh), the one table of formats by extension (registry), pictures and renders."""
