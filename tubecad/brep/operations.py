"""OCCT's builders of arguments and tools (the booleans, the General Fuse splitter) given
their shapes and built: the one place the argument and tool lists are filled."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TypeVar

from OCP.TopoDS import TopoDS_Shape

from tubecad.occ_compat import ListOfShape

#: a builder with SetArguments, SetTools, SetRunParallel and Build (BRepAlgoAPI_Fuse, _Cut, _Splitter)
Operation = TypeVar("Operation")


def built(
    operation: Operation, arguments: Iterable[TopoDS_Shape], tools: Iterable[TopoDS_Shape], *, parallel: bool = False
) -> Operation:
    """``operation`` given ``arguments`` and ``tools`` and built (OCCT's own threads where
    ``parallel``); the caller reads its ``IsDone``, ``Shape`` and history.

    Args:
        operation: a new BRepAlgoAPI builder (a boolean or the splitter).
        arguments: its arguments.
        tools: its tools.
        parallel: whether OCCT may run it on several threads.

    Returns:
        The same builder, built.
    """
    listed_arguments, listed_tools = ListOfShape(), ListOfShape()
    for shape in arguments:
        listed_arguments.Append(shape)
    for shape in tools:
        listed_tools.Append(shape)
    operation.SetArguments(listed_arguments)  # type: ignore[attr-defined]
    operation.SetTools(listed_tools)  # type: ignore[attr-defined]
    operation.SetRunParallel(parallel)  # type: ignore[attr-defined]
    operation.Build()  # type: ignore[attr-defined]
    return operation
