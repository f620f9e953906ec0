"""CAD files: STEP (AP214 or AP242), IGES (B-rep mode) and BREP.

Every write goes to a temporary file that replaces the target only when complete.
The format follows the file extension (tubecad.export.registry lists every extension,
including the mesh and polyline formats).

STEP is always written through OCCT's XCAF writer (STEPCAFControl_Writer, as build123d's
``export_step`` does), so every file carries product names: the file's name for a single
solid, the labels (``wall``, ``ring_03``, ...) and colours of a build123d assembly. The
schema is one of OCCT's global settings (``write.step.schema``); :func:`step_settings`
sets it for one write only, after the STEP controllers exist (their first initialisation
would reset it), and restores the previous value afterwards.

Both are written with every real to 17 significant digits (:data:`FILE_REAL`): a double to
the bit, so the file's surfaces are the built ones (OCCT's writers alone write 13 digits for
STEP and 9 decimals for IGES).

Length units (tubecad.core.units): the coordinates are written as they are, in the model's
unit (``length_unit``, default mm), and the file says which unit that is: STEP's
SI_UNIT / CONVERSION_BASED_UNIT (the XCAF document's length unit and ``write.step.unit``
both set to it, so OCCT scales nothing) and the IGES global section's unit flag and name
(with the model's cascade unit set to it). BREP holds no unit. OCCT's readers convert a
file into ``xstep.cascade.unit`` (millimetres by default, as build123d's ``import_step``
does); :func:`import_shape` reads in the unit asked.
"""

from __future__ import annotations

import contextlib
import re
from collections.abc import Iterator
from datetime import UTC
from pathlib import Path
from typing import TYPE_CHECKING

from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.BRep import BRep_Builder
from OCP.BRepTools import BRepTools
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Controller, IGESControl_Reader, IGESControl_Writer
from OCP.IGESData import IGESData_IGESWriter
from OCP.IGESSelect import IGESSelect_WorkLibrary
from OCP.Interface import Interface_Static
from OCP.Message import Message, Message_PrinterOStream
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Reader, STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Controller, STEPControl_Reader, STEPControl_Writer
from OCP.StepData import StepData_Protocol, StepData_StepWriter
from OCP.TCollection import TCollection_ExtendedString, TCollection_HAsciiString
from OCP.TDataStd import TDataStd_Name
from OCP.TDF import TDF_Label
from OCP.TopoDS import TopoDS_Shape
from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool
from OCP.XSControl import XSControl_WorkSession

from tubecad.brep.properties import topods
from tubecad.core.atomic import atomic_path
from tubecad.core.errors import ParameterError, TubecadError
from tubecad.core.units import DEFAULT_LENGTH_UNIT
from tubecad.core.units import length_unit as unit_of
from tubecad.export.formats import cad_format
from tubecad.occ_compat import IndexedMapOfShape, LabelSequence, downcast

if TYPE_CHECKING:
    import build123d as bd

STEP_SCHEMAS = {"AP214": "AP214IS", "AP242": "AP242DIS"}

#: how STEP and IGES write a real: 17 significant digits, as many as a double holds, so a
#: file's numbers read back to the bit and its surfaces are the built ones (tested). OCCT's
#: writers alone write 13 (STEP: "%.12f" or "%.12E") or 9 decimals (IGES), and the rounding
#: shows where the poles are close together: the paper's wall at [fit] tolerance 1e-10 read
#: back from 13 digits has isolines |cos| 5.9e-11 apart at a face's corner, where the fit
#: holds 4.8e-12. The writers' own zero suppression cuts a number longer than 16 characters
#: short, so it is off: STEP's numbers are shortened afterwards (:func:`_shortened_reals`,
#: trailing zeros and E+00 dropped); IGES keeps them (its card images have fixed columns),
#: about twice OCCT's own IGES file.
FILE_REAL = "%.16E"

#: the old name of FILE_REAL, kept importable
IGES_REAL = FILE_REAL

#: one real as FILE_REAL writes it, in a STEP file's data: its trailing zeros and E+00 are dropped
_REAL = re.compile(rb"(?<=[(,\s])(-?\d\.\d*?)0*E([+-]\d\d)(?=[,)\s])")


class ExportError(TubecadError):
    """OCCT failed to write or read a CAD file."""


def write_cad(
    fmt: str,
    shape: object,
    path: str | Path,
    step_schema: str = "AP214",
    name: str = "tubecad",
    length_unit: str = DEFAULT_LENGTH_UNIT,
) -> None:
    """Write ``shape`` in ``fmt`` ('step', 'iges' or 'brep') to ``path`` as it is (not atomic),
    its coordinates in ``length_unit`` (BREP holds no unit)."""
    _quiet()
    if fmt == "step":
        write_step(shape, path, step_schema, name, length_unit)
    elif fmt == "iges":
        _write_iges(topods(shape), Path(path), length_unit)
    else:
        _write_brep(topods(shape), Path(path))


@contextlib.contextmanager
def step_settings(schema: str = "AP214", length_unit: str = DEFAULT_LENGTH_UNIT) -> Iterator[None]:
    """OCCT's STEP write settings (schema, length unit) for the writes inside the block only.

    The STEP controllers are initialised first: their first initialisation in a process
    creates the settings with their defaults, so a value set before it would be lost.
    The previous values are restored afterwards, so other writers in the process (a plain
    STEPControl_Writer, CadQuery's exportStep) keep theirs.
    """
    if schema not in STEP_SCHEMAS:
        raise ParameterError(f"step_schema must be one of {', '.join(STEP_SCHEMAS)}, got {schema!r}")
    STEPControl_Controller.Init_s()
    STEPCAFControl_Controller.Init_s()
    wanted = {"write.step.schema": STEP_SCHEMAS[schema], "write.step.unit": unit_of(length_unit).step}
    saved = {key: Interface_Static.CVal_s(key) for key in wanted}
    try:
        for key, value in wanted.items():
            Interface_Static.SetCVal_s(key, value)
        yield
    finally:
        for key, value in saved.items():
            Interface_Static.SetCVal_s(key, value)


def write_step(
    shape: object,
    path: str | Path,
    schema: str = "AP214",
    name: str = "tubecad",
    length_unit: str = DEFAULT_LENGTH_UNIT,
) -> None:
    """Write ``shape`` to STEP at ``path`` (not atomic) with OCCT's XCAF writer: names and
    colours of a build123d assembly are kept, and the top product is called ``name``. The
    coordinates are in ``length_unit``, and the file says so."""
    import build123d as bd
    from build123d.exporters3d import _create_xde  # the XCAF document export_step writes

    _quiet()
    node = shape if isinstance(shape, bd.Shape) else bd.Shape.cast(topods(shape))
    if node.parent is not None:  # a part of an assembly, written on its own: the XCAF document needs a root
        part = bd.Shape.cast(node.wrapped)
        part.label, part.color = node.label, node.color
        node = part if not node.children else bd.Compound(children=[bd.Shape.cast(c.wrapped) for c in node.children])
    unit = unit_of(length_unit)
    # the document's unit and write.step.unit agree, so the writer scales nothing
    doc = _create_xde(node, bd.Unit[unit.build123d], auto_naming=True)
    shape_tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    roots = LabelSequence()
    shape_tool.GetFreeShapes(roots)
    for i in range(1, roots.Length() + 1):
        TDataStd_Name.Set_s(roots.Value(i), TCollection_ExtendedString(name))
    with step_settings(schema, unit.name), _declared_uncertainty(node.wrapped):
        writer = STEPCAFControl_Writer(XSControl_WorkSession(), False)
        writer.SetColorMode(True)
        writer.SetLayerMode(True)
        writer.SetNameMode(True)
        if not writer.Transfer(doc, STEPControl_AsIs):
            raise ExportError(f"OCCT could not translate the shape to STEP for {str(path)!r}")
        # the header exists once the shape is transferred; an empty header made before
        # (as build123d's export_step does) would fix FILE_SCHEMA to AP214
        header = APIHeaderSection_MakeHeader(writer.Writer().Model())
        if header.IsDone():
            header.SetName(TCollection_HAsciiString(name))
            header.SetOriginatingSystem(TCollection_HAsciiString("tubecad"))
            stamp = _source_date()
            if stamp is not None:  # reproducible builds: the same spec, the same bytes
                header.SetTimeStamp(TCollection_HAsciiString(stamp))
        _print_step(writer.Writer(), Path(path))


def _print_step(writer: STEPControl_Writer, path: Path) -> None:
    """What ``writer.Write(path)`` does (StepSelect_WorkLibrary::WriteFile: the model sent to
    a StepData_StepWriter and printed), with every real to 17 significant digits
    (:data:`FILE_REAL`), shortened by :func:`_shortened_reals`."""
    import io

    step = StepData_StepWriter(writer.Model())
    step.FloatWriter().SetFormat(FILE_REAL, True)  # True: no second format for 0.1 <= |x| < 1000
    step.FloatWriter().SetZeroSuppress(False)  # it would cut 17 digits short
    step.SendModel(downcast(writer.WS().Protocol(), StepData_Protocol))
    buffer = io.BytesIO()
    if not step.Print(buffer):
        raise ExportError(f"OCCT could not write STEP to {str(path)!r}")
    path.write_bytes(_shortened_reals(buffer.getvalue()))


def _shortened_reals(text: bytes) -> bytes:
    """STEP data with each real of :data:`FILE_REAL` written shortest: 1.5000000000000000E+02
    as 1.5E+02, 2.0000000000000000E+00 as 2., the same numbers (ISO 10303-21 reals)."""
    return _REAL.sub(lambda m: m[1] + (b"" if m[2] == b"+00" else b"E" + m[2]), text)


def _source_date() -> str | None:
    """SOURCE_DATE_EPOCH (the reproducible-builds convention), as STEP's ISO 8601 time stamp,
    or None when it is not set (OCCT then writes the current time)."""
    import os
    from datetime import datetime

    value = os.environ.get("SOURCE_DATE_EPOCH")
    if not value or not value.strip().isdigit():
        return None
    return datetime.fromtimestamp(int(value), tz=UTC).strftime("%Y-%m-%dT%H:%M:%S")


def step_names(path: str | Path) -> list[tuple[int, str]]:
    """The product and component names of a STEP file as OCCT's XCAF reader sees them:
    (depth, name) in tree order, depth 0 for the top products."""
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFApp import XCAFApp_Application

    _quiet()
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    XCAFApp_Application.GetApplication_s().NewDocument(TCollection_ExtendedString("MDTV-XCAF"), doc)
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    if reader.ReadFile(str(path)) != IFSelect_RetDone or not reader.Transfer(doc):
        raise ExportError(f"cannot read STEP file {str(path)!r}")
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    out: list[tuple[int, str]] = []

    def name_of(label: TDF_Label) -> str:
        attr = TDataStd_Name()
        return attr.Get().ToExtString() if label.FindAttribute(TDataStd_Name.GetID_s(), attr) else ""

    def visit(label: TDF_Label, depth: int) -> None:
        out.append((depth, name_of(label)))
        referred = TDF_Label()
        if XCAFDoc_ShapeTool.IsReference_s(label) and XCAFDoc_ShapeTool.GetReferredShape_s(label, referred):
            label = referred
        children = LabelSequence()
        XCAFDoc_ShapeTool.GetComponents_s(label, children, False)
        for i in range(1, children.Length() + 1):
            visit(children.Value(i), depth + 1)

    roots = LabelSequence()
    tool.GetFreeShapes(roots)
    for i in range(1, roots.Length() + 1):
        visit(roots.Value(i), 0)
    return out


def read_faces(path: str | Path, length_unit: str = DEFAULT_LENGTH_UNIT) -> list[tuple[str, TopoDS_Shape]]:
    """The faces of a STEP file in the file's order (OCCT's explorer over its free shapes,
    each placed), in ``length_unit``, with their names: a face's own name where the file gives
    one, else the name of the smallest named shape that holds it alone (a product of one face),
    else ``""``.

    Args:
        path: the STEP file.
        length_unit: the unit the coordinates are read into.

    Returns:
        [(name, face)], the faces as TopoDS_Shape (downcast with ``occ_compat.as_face``).

    Raises:
        ExportError: the file cannot be read.
    """
    from OCP.TDocStd import TDocStd_Document
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.XCAFApp import XCAFApp_Application

    _quiet()
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    XCAFApp_Application.GetApplication_s().NewDocument(TCollection_ExtendedString("MDTV-XCAF"), doc)
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    with _static("xstep.cascade.unit", unit_of(length_unit).step):
        if reader.ReadFile(str(path)) != IFSelect_RetDone or not reader.Transfer(doc):
            raise ExportError(f"cannot read STEP file {str(path)!r}")
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    faces = IndexedMapOfShape()
    names: dict[int, tuple[int, str]] = {}  # face index -> (faces in the named shape, name)

    def name_of(label: TDF_Label) -> str:
        attr = TDataStd_Name()
        return attr.Get().ToExtString() if label.FindAttribute(TDataStd_Name.GetID_s(), attr) else ""

    def visit(label: TDF_Label, shape: TopoDS_Shape) -> None:
        inside = []
        explorer = TopExp_Explorer(shape, TopAbs_FACE)
        while explorer.More():
            inside.append(faces.Add(explorer.Current()))
            explorer.Next()
        referred = TDF_Label()
        if XCAFDoc_ShapeTool.IsReference_s(label) and XCAFDoc_ShapeTool.GetReferredShape_s(label, referred):
            name = name_of(label) or name_of(referred)  # an instance's name, else its product's
            label = referred
        else:
            name = name_of(label)
        for index in inside if name else ():
            if len(set(inside)) < names.get(index, (1 << 30, ""))[0]:
                names[index] = (len(set(inside)), name)
        components = LabelSequence()
        XCAFDoc_ShapeTool.GetComponents_s(label, components, False)
        for i in range(1, components.Length() + 1):
            component = components.Value(i)
            visit(component, XCAFDoc_ShapeTool.GetShape_s(component).Moved(shape.Location()))
        subs = LabelSequence()
        if XCAFDoc_ShapeTool.GetSubShapes_s(label, subs):
            for i in range(1, subs.Length() + 1):
                sub = subs.Value(i)
                visit(sub, XCAFDoc_ShapeTool.GetShape_s(sub).Located(shape.Location()))

    roots = LabelSequence()
    tool.GetFreeShapes(roots)
    for i in range(1, roots.Length() + 1):
        visit(roots.Value(i), XCAFDoc_ShapeTool.GetShape_s(roots.Value(i)))
    return [(names.get(i, (0, ""))[1], faces.FindKey(i)) for i in range(1, faces.Extent() + 1)]


def import_shape(path: str | Path, length_unit: str = DEFAULT_LENGTH_UNIT) -> TopoDS_Shape:
    """Read a STEP, IGES or BREP file back into one OCCT shape, its coordinates converted
    from the file's unit into ``length_unit`` (default mm, as OCCT and build123d read; BREP
    holds no unit and is read as it is)."""
    fmt = cad_format(path)
    _quiet()
    if fmt == "brep":
        shape = TopoDS_Shape()
        if not BRepTools.Read_s(shape, str(path), BRep_Builder()):
            raise ExportError(f"cannot read BREP file {str(path)!r}")
        return shape
    (STEPControl_Controller if fmt == "step" else IGESControl_Controller).Init_s()
    reader = STEPControl_Reader() if fmt == "step" else IGESControl_Reader()
    with _static("xstep.cascade.unit", unit_of(length_unit).step):  # the unit the reader converts into
        if reader.ReadFile(str(path)) != IFSelect_RetDone:
            raise ExportError(f"cannot read {fmt.upper()} file {str(path)!r}")
        reader.TransferRoots()
    return reader.OneShape()


@contextlib.contextmanager
def _static(key: str, value: str) -> Iterator[None]:
    """OCCT's global setting ``key`` set to ``value`` inside the block only."""
    saved = Interface_Static.CVal_s(key)
    if not Interface_Static.SetCVal_s(key, value):
        raise ExportError(f"OCCT does not accept {key} = {value!r}")
    try:
        yield
    finally:
        Interface_Static.SetCVal_s(key, saved)


@contextlib.contextmanager
def _declared_uncertainty(shape: TopoDS_Shape) -> Iterator[None]:
    """The uncertainty the file declares, for the writes inside the block: the policy's
    :func:`~tubecad.core.tolerance.file_uncertainty` for the shape's largest coordinate
    where it asks for one (OCCT's reader heals the B-rep to the file's uncertainty; at the
    default 1e-7 a solid with coordinates of 1e6, held to 6e-7, reads back invalid)."""
    from tubecad.brep.properties import largest_coordinate
    from tubecad.core.tolerance import file_uncertainty

    value = file_uncertainty(largest_coordinate(shape))
    if value is None:
        yield
        return
    with _static("write.precision.mode", "2"), _static("write.precision.val", repr(value)):  # 2: the given value
        yield


def _write_iges(shape: TopoDS_Shape, path: Path, length_unit: str = DEFAULT_LENGTH_UNIT) -> None:
    from tubecad.brep.properties import largest_coordinate
    from tubecad.core.tolerance import file_uncertainty

    IGESControl_Controller.Init_s()
    unit = unit_of(length_unit)
    writer = IGESControl_Writer(unit.step, 1)  # the file's unit; 1: B-rep entities (solids and shells survive)
    # the model's coordinates are in that unit too (as IGESCAFControl_Writer sets from a
    # document's length unit), so nothing is scaled
    section = writer.Model().GlobalSection()
    section.SetCascadeUnit(unit.mm)
    uncertainty = file_uncertainty(largest_coordinate(shape))
    if uncertainty is not None:  # as for STEP: the resolution the reader heals the B-rep to
        section.SetResolution(uncertainty)
    writer.Model().SetGlobalSection(section)
    if not writer.AddShape(shape):
        raise ExportError("OCCT could not translate the shape to IGES")
    writer.ComputeModel()
    # IGESControl_Writer.Write, with the numbers written to 17 significant digits (FILE_REAL)
    # instead of its fixed 9 decimals
    iges = IGESData_IGESWriter(writer.Model())
    iges.FloatWriter().SetFormat(FILE_REAL, True)  # True: no second format for 0.1 <= |x| < 1000
    iges.FloatWriter().SetZeroSuppress(False)  # it would cut 17 digits short
    try:
        if writer.Model().NbEntities() == 0:
            raise OSError("no entities")
        iges.SendModel(IGESSelect_WorkLibrary.DefineProtocol_s())
        with open(path, "wb") as stream:
            # the stubs type OCP's std::ostream as io.BytesIO; OCP writes to any binary file object
            if not iges.Print(stream):  # type: ignore[arg-type]
                raise OSError("IGESData_IGESWriter.Print failed")
    except OSError as exc:
        raise ExportError(f"OCCT could not write IGES to {str(path)!r}") from exc


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


def export_named_step(
    assembly: bd.Compound,
    path: str | Path,
    step_schema: str = "AP214",
    name: str | None = None,
    length_unit: str = "mm",
) -> Path:
    """Write the assembly to STEP (``step_schema``, coordinates in ``length_unit``, which the
    file states) with its names and colours, atomically; the top product is ``name``
    (default: the file's stem)."""
    with atomic_path(path) as tmp:
        write_step(assembly, tmp, step_schema, name or Path(path).stem, length_unit)
    return Path(path)
