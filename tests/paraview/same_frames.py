# pvpython same_frames.py ONE MANY: ParaView opens two run folders of one scenario, one run in one process
# (.vti, .vtp) and one over MPI ranks (.pvti, .pvtp pieces), and finds the same arrays with the same values in
# every frame of wind.pvd, trees.pvd and, where the run has leaves, leaves.pvd (the trees matched by tree_id
# and node_id, the leaves by tree_id and position, as pieces list them rank by rank). A manual check (pvpython is not in CI; tests/tools/compare_runs.cpp is CI's check), see
# docs/parallel.md.
import sys
from paraview.simple import *
from paraview import servermanager
from vtk.numpy_interface import dataset_adapter as dsa
import numpy as np
import os
one, many = sys.argv[1], sys.argv[2]
for name in ["wind", "trees", "leaves"]:
    if not os.path.exists(one + "/" + name + ".pvd"):
        continue
    a = OpenDataFile(one + "/" + name + ".pvd")
    b = OpenDataFile(many + "/" + name + ".pvd")
    times = a.TimestepValues
    assert list(times) == list(b.TimestepValues), (times, b.TimestepValues)
    for t in times:
        a.UpdatePipeline(t); b.UpdatePipeline(t)
        da = dsa.WrapDataObject(servermanager.Fetch(a)); db = dsa.WrapDataObject(servermanager.Fetch(b))
        data_a = da.CellData if name == "wind" else da.PointData
        data_b = db.CellData if name == "wind" else db.PointData
        names = list(data_a.keys())
        assert names == list(data_b.keys()), (names, list(data_b.keys()))
        if name == "trees":
            # pieces list trees rank by rank: order both by (tree_id, node_id)
            oa = np.lexsort((data_a["node_id"], data_a["tree_id"])); ob = np.lexsort((data_b["node_id"], data_b["tree_id"]))
            assert np.array_equal(np.asarray(da.Points)[oa], np.asarray(db.Points)[ob])
        elif name == "leaves":
            # a leaf's file has no index of it: order both by tree_id and position
            pa = np.asarray(da.Points); pb = np.asarray(db.Points)
            oa = np.lexsort((pa[:, 2], pa[:, 1], pa[:, 0], data_a["tree_id"]))
            ob = np.lexsort((pb[:, 2], pb[:, 1], pb[:, 0], data_b["tree_id"]))
            assert np.array_equal(pa[oa], pb[ob])
        else:
            oa = ob = slice(None)
            assert da.GetDimensions() == db.GetDimensions()
        for n in names:
            assert np.array_equal(np.asarray(data_a[n])[oa], np.asarray(data_b[n])[ob]), (name, t, n)
        print(name, "t =", t, "arrays", names, "equal;", "cells" if name == "wind" else "points",
              da.GetNumberOfCells() if name == "wind" else da.GetNumberOfPoints())
print("ParaView", GetParaViewVersion(), ": identical")
