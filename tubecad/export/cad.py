"""CAD files: STEP (AP214 or AP242, millimetres), IGES (B-rep mode) and BREP.

Every write goes to a temporary file that replaces the target only when complete.
The format follows the file extension (.step/.stp, .iges/.igs, .brep).
"""

from __future__ import annotations

from pathlib import Path

from OCP.BRep import BRep_Builder
from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Controller, IGESControl_Reader, IGESControl_Writer
from OCP.Interface import Interface_Static
from OCP.Message import Message, Message_PrinterOStream
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.TopoDS import TopoDS_Shape

from ..brep.properties import topods
from ..errors import ParameterError, TubecadError
from .atomic import atomic_path

FORMATS = {".step": "step", ".stp": "step", ".iges": "iges", ".igs": "iges", ".brep": "brep"}
STEP_SCHEMAS = {"AP214": "AP214IS", "AP242": "AP242DIS"}


class ExportError(TubecadError):
    """OCCT failed to write or read a CAD file."""


def cad_format(path: str | Path) -> str:
    """'step', 'iges' or 'brep' from the extension, or a ParameterError listing them."""
    fmt = FORMATS.get(Path(path).suffix.lower())
    if fmt is None:
        raise ParameterError(f"output {str(path)!r}: unknown extension; use one of {', '.join(FORMATS)}")
    return fmt


def export_shape(shape, path: str | Path, step_schema: str = "AP214") -> Path:
    """Write ``shape`` (OCCT or build123d/CadQuery) to ``path`` in the format of its extension."""
    fmt = cad_format(path)
    _quiet()
    with atomic_path(path) as tmp:
        {"step": lambda: _write_step(topods(shape), tmp, step_schema),
         "iges": lambda: _write_iges(topods(shape), tmp),
         "brep": lambda: _write_brep(topods(shape), tmp)}[fmt]()  # fmt: skip
    return Path(path)


def import_shape(path: str | Path) -> TopoDS_Shape:
    """Read a STEP, IGES or BREP file back into one OCCT shape."""
    fmt = cad_format(path)
    _quiet()
    if fmt == "brep":
        shape = TopoDS_Shape()
        if not BRepTools.Read_s(shape, str(path), BRep_Builder()):
            raise ExportError(f"cannot read BREP file {str(path)!r}")
        return shape
    reader = STEPControl_Reader() if fmt == "step" else IGESControl_Reader()
    if reader.ReadFile(str(path)) != IFSelect_RetDone:
        raise ExportError(f"cannot read {fmt.upper()} file {str(path)!r}")
    reader.TransferRoots()
    return reader.OneShape()


def _write_step(shape: TopoDS_Shape, path: Path, schema: str) -> None:
    if schema not in STEP_SCHEMAS:
        raise ParameterError(f"step_schema must be one of {', '.join(STEP_SCHEMAS)}, got {schema!r}")
    Interface_Static.SetCVal_s("write.step.schema", STEP_SCHEMAS[schema])
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    writer = STEPControl_Writer()
    if writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone or writer.Write(str(path)) != IFSelect_RetDone:
        raise ExportError(f"OCCT could not write STEP to {str(path)!r}")


def _write_iges(shape: TopoDS_Shape, path: Path) -> None:
    IGESControl_Controller.Init_s()
    writer = IGESControl_Writer("MM", 1)  # 1: B-rep entities (solids and shells survive)
    if not writer.AddShape(shape):
        raise ExportError("OCCT could not translate the shape to IGES")
    writer.ComputeModel()
    if not writer.Write(str(path)):
        raise ExportError(f"OCCT could not write IGES to {str(path)!r}")


def _write_brep(shape: TopoDS_Shape, path: Path) -> None:
    if not BRepTools.Write_s(shape, str(path)):
        raise ExportError(f"OCCT could not write BREP to {str(path)!r}")


_quieted = False


def _quiet() -> None:
    """Silence OCCT's translator chatter on stdout (once)."""
    global _quieted
    if not _quieted:
        Message.DefaultMessenger_s().RemovePrinters(Message_PrinterOStream.get_type_descriptor_s())
        _quieted = True
