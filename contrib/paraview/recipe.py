# contrib/paraview/recipe.py — the ParaView recipe of docs/output.md ("Viewing in ParaView"),
# step by step with the same filters in the same order, run by pvbatch: so that the recipe the
# docs give is one that has been run. It opens DIR's bodies.pvd, contacts.pvd and springs.pvd
# (DIR or DIR/vtk, as the drivers write them), goes to the last time step, builds
#   contacts -> Threshold (rn > 0) -> Cell Data to Point Data -> Extract Surface -> Tube (radius by rn)
# and the springs' tubes the same way, checks that every stage has cells, prints one line per
# stage and saves a screenshot. Exit status 0 when the recipe works, 1 when a stage is empty or
# fails (a Tube fed by Threshold without Extract Surface produces nothing: "vtkUnstructuredGrid,
# but a vtkPolyData is required"), 2 for bad arguments.
#
#   xvfb-run -a pvbatch contrib/paraview/recipe.py out/ballast -o recipe.png
#
# (pvbatch, not pvpython: see contrib/paraview/README.md, "ParaView's Python on Debian 12".)
import argparse
import os
import sys


def main(argv):
    p = argparse.ArgumentParser(prog="pvbatch recipe.py", description="Run docs/output.md's ParaView recipe on a run's VTK output.")
    p.add_argument("directory", help="folder holding bodies.pvd and contacts.pvd (or its vtk/ subfolder)")
    p.add_argument("-o", "--output", default=None, help="PNG to write (default: none)")
    p.add_argument("--no-extract-surface", action="store_true",
                   help="leave out Extract Surface (to see the recipe fail without it)")
    args = p.parse_args(argv)
    d = args.directory
    if not os.path.isfile(os.path.join(d, "contacts.pvd")):
        d = os.path.join(d, "vtk")
    for name in ("bodies.pvd", "contacts.pvd"):
        if not os.path.isfile(os.path.join(d, name)):
            print("recipe: no %s in %s nor in %s/vtk" % (name, args.directory, args.directory), file=sys.stderr)
            return 2
    try:
        import paraview.simple as pv
    except ImportError as e:
        print("recipe: ParaView's Python modules are missing (%s): run it with pvbatch (contrib/paraview/README.md)" % e,
              file=sys.stderr)
        return 2

    failed = []

    def check(what, src):
        src.UpdatePipeline(t)
        n = src.GetDataInformation().GetNumberOfCells()
        print("recipe: %-44s %6d cells" % (what, n))
        if n == 0:
            failed.append(what)
        return n

    # 1. File > Open bodies.pvd, Apply; the time controls: go to the last frame.
    bodies = pv.PVDReader(FileName=os.path.join(d, "bodies.pvd"))
    times = list(bodies.TimestepValues) if bodies.TimestepValues else [0.0]
    t = times[-1]
    view = pv.CreateView("RenderView")
    pv.SetActiveView(view)
    view.ViewTime = t
    check("bodies.pvd", bodies)
    # 2. Colour by velocity (Magnitude).
    rep = pv.Show(bodies, view)
    pv.ColorBy(rep, ("CELLS", "velocity", "Magnitude"))
    # 3. Force network: contacts.pvd -> Threshold rn > 0 -> Cell Data to Point Data
    #    -> Extract Surface -> Tube, Vary Radius By Scalar rn, coloured by rn.
    contacts = pv.PVDReader(FileName=os.path.join(d, "contacts.pvd"))
    check("contacts.pvd", contacts)
    threshold = pv.Threshold(Input=contacts)
    threshold.Scalars = ["CELLS", "rn"]
    if hasattr(threshold, "LowerThreshold"):  # ParaView >= 5.10
        threshold.ThresholdMethod = "Above Upper Threshold"
        threshold.UpperThreshold = 1e-12
    else:
        threshold.ThresholdRange = [1e-12, 1e300]
    check("Threshold (rn > 0)", threshold)
    points = pv.CellDatatoPointData(Input=threshold)
    check("Cell Data to Point Data", points)
    lines = points if args.no_extract_surface else pv.ExtractSurface(Input=points)
    if not args.no_extract_surface:
        check("Extract Surface", lines)
    tube = pv.Tube(Input=lines)
    tube.Scalars = ["POINTS", "rn"]
    tube.VaryRadius = "By Scalar"
    tube.Radius = 5e-4
    tube.RadiusFactor = 4.0
    check("Tube (Vary Radius By Scalar rn)", tube)
    trep = pv.Show(tube, view)
    pv.ColorBy(trep, ("POINTS", "rn"))
    # 4. Springs (runs with a sublayer): colour by strain, Tube as for the contacts.
    if os.path.isfile(os.path.join(d, "springs.pvd")):
        springs = pv.PVDReader(FileName=os.path.join(d, "springs.pvd"))
        check("springs.pvd", springs)
        sp = pv.CellDatatoPointData(Input=springs)  # springs are PolyData already: no Extract Surface
        stube = pv.Tube(Input=sp)
        stube.Radius = 1e-3
        check("springs: Cell Data to Point Data -> Tube", stube)
        srep = pv.Show(stube, view)
        pv.ColorBy(srep, ("POINTS", "strain"))
    if args.output:
        view.ViewSize = [1200, 700]
        pv.ResetCamera(view)
        pv.SaveScreenshot(args.output, view)
        print("recipe: wrote %s" % args.output)
    if failed:
        print("recipe: FAILED, empty: %s" % ", ".join(failed), file=sys.stderr)
        return 1
    print("recipe: ok (time %g s, frame %d of %d)" % (t, len(times) - 1, len(times)))
    return 0


status = main(sys.argv[1:])
if status:  # a plain end for success: pvbatch's sys.exit(0) tears the render window down badly
    sys.exit(status)
