#!/usr/bin/python3
"""A picture of a solid's surface field (mfree run of a solid scene): the triangles of
surface.vtu, displaced by `scale` times u^h, coloured by a point field averaged over each
triangle's corners.

usage: plot_solid.py SURFACE.vtu OUT.png [FIELD [SCALE [TITLE [AZIMUTH]]]]
FIELD defaults to von_mises, SCALE to 0 (the undeformed surface), AZIMUTH (degrees, the view
round z) to 35. Writes OUT.png (a temporary
file, then renamed).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader  # noqa: E402


def main():
    path, out = sys.argv[1], sys.argv[2]
    field = sys.argv[3] if len(sys.argv) > 3 else "von_mises"
    scale = float(sys.argv[4]) if len(sys.argv) > 4 else 0.0
    title = sys.argv[5] if len(sys.argv) > 5 else f"{field} on {os.path.basename(path)}"
    azimuth = float(sys.argv[6]) if len(sys.argv) > 6 else 35.0
    if not os.path.isfile(path):
        sys.exit(f"{path}: no such file (a solid run with [output] fields writes surface.vtu)")
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData()).copy()
    data = grid.GetPointData()
    if data.GetArray(field) is None:
        sys.exit(f"{path}: no point field '{field}'")
    values = vtk_to_numpy(data.GetArray(field))
    if values.ndim > 1:
        values = np.linalg.norm(values, axis=1)
    if scale != 0.0:
        points += scale * vtk_to_numpy(data.GetArray("displacement"))
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 3)
    faces = points[cells]
    face_values = values[cells].mean(axis=1)
    norm = matplotlib.colors.Normalize(vmin=face_values.min(), vmax=face_values.max())
    colours = matplotlib.cm.viridis(norm(face_values))
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(faces, facecolors=colours, edgecolors="none"))
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for set_lim, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        set_lim(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.view_init(elev=25, azim=azimuth)
    fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=ax, shrink=0.7, label=field)
    ax.set_title(title)
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=100)
    os.replace(tmp, out)
    plt.close(fig)


if __name__ == "__main__":
    main()
