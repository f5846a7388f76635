"""A field snapshot written in pieces on N ranks (.pvtu, docs/fem-soil.md "On many ranks")
against one process's (.vtu), both read by VTK's own readers (ParaView's): the parallel file
opens with vtkXMLPUnstructuredGridReader, its points not marked as ghosts (vtkGhostType 0) are
as many as the one-process file's points, each is at one of its points, and there the
displacement and the velocity agree to TOLERANCE of their largest value; every ghost copy holds
its owner's values bit for bit.

usage: python3 pvtu_agrees.py MANY.pvtu ONE.vtu TOLERANCE
exit 0: agree; 1: differ (said why); 2: VTK's Python module missing or a file unreadable."""
import sys

try:
    from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
except ImportError as e:
    print(f"pvtu_agrees: VTK's Python module is missing ({e}); install Debian's python3-vtk9 "
          "(tools/install_dependencies.sh lists it)")
    sys.exit(2)
import numpy as np


def read(reader, path):
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or grid.GetNumberOfPoints() == 0:
        print(f"pvtu_agrees: {path}: no points read")
        sys.exit(2)
    data = grid.GetPointData()
    arrays = {name: vtk_to_numpy(data.GetArray(name)) for name in ("displacement", "velocity")}
    ghosts = data.GetArray("vtkGhostType")
    arrays["ghost"] = (vtk_to_numpy(ghosts) if ghosts is not None
                       else np.zeros(grid.GetNumberOfPoints(), dtype=np.uint8))
    return vtk_to_numpy(grid.GetPoints().GetData()), arrays, grid.GetNumberOfCells()


def main():
    many_path, one_path, tolerance = sys.argv[1], sys.argv[2], float(sys.argv[3])
    many_points, many, many_cells = read(vtkXMLPUnstructuredGridReader(), many_path)
    one_points, one, one_cells = read(vtkXMLUnstructuredGridReader(), one_path)
    owned = many["ghost"] == 0
    print(f"pvtu_agrees: {many_path}: {len(many_points)} points in its pieces, "
          f"{int(owned.sum())} not ghosts, {many_cells} cells; {one_path}: {len(one_points)} "
          f"points, {one_cells} cells")
    if owned.sum() != len(one_points) or many_cells != one_cells:
        print("pvtu_agrees: FAILED: the point or cell counts differ")
        return 1
    where = {tuple(p): k for k, p in enumerate(one_points)}
    try:
        index = np.array([where[tuple(p)] for p in many_points[owned]])
    except KeyError as e:
        print(f"pvtu_agrees: FAILED: a point of the pieces is none of one process's: {e}")
        return 1
    if len(np.unique(index)) != len(one_points):
        print("pvtu_agrees: FAILED: two owned points at one place")
        return 1
    worst = 0.0
    for name in ("displacement", "velocity"):
        scale = np.abs(one[name]).max()
        gap = np.abs(many[name][owned] - one[name][index]).max()
        differ = gap / scale if scale > 0.0 else (0.0 if gap == 0.0 else np.inf)
        print(f"pvtu_agrees: {name}: largest {scale:.6g}, differs by {differ:.3g} of it")
        worst = max(worst, differ)
    # Every copy of a shared node holds its owner's value, bit for bit (docs/fem-soil.md, "On
    # many ranks"): each ghost against the owned copy at its place in the same pieces.
    owned_at = {tuple(p): k for k, p in zip(np.flatnonzero(owned), many_points[owned])}
    ghost_owner = np.array([owned_at[tuple(p)] for p in many_points[~owned]], dtype=int)
    unequal = np.zeros(len(ghost_owner), dtype=bool)
    for name in ("displacement", "velocity"):
        unequal |= np.any(many[name][~owned] != many[name][ghost_owner], axis=-1)
    copies = int(unequal.sum())
    print(f"pvtu_agrees: {int((~owned).sum())} ghost copies, {copies} of them not their "
          "owners' values bit for bit")
    if worst > tolerance:
        print(f"pvtu_agrees: FAILED: above the tolerance {tolerance:g}")
        return 1
    if copies > 0:
        print("pvtu_agrees: FAILED: a ghost copy differs from its owner's value")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
