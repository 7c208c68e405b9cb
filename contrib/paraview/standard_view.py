# contrib/paraview/standard_view.py — the standard view of a run's VTK output as a ParaView Python
# state: grains coloured by speed (fixed bodies grey), the force chains as tubes (radius and colour by rn), the springs
# (runs with a sublayer) as tubes coloured by rn, all following ParaView's time controls. Open it in
# the ParaView GUI with one command, the run's output folder (or its vtk/) in NSCD_VTK:
#
#   NSCD_VTK=out/datbox_disks paraview --script=contrib/paraview/standard_view.py
#
# or render the last frame to a PNG without the GUI (pvbatch, see README.md):
#
#   xvfb-run -a pvbatch contrib/paraview/standard_view.py out/datbox_disks -o view.png
#
# The pipeline is docs/output.md's recipe ("Viewing in ParaView"), which recipe.py checks stage by
# stage: contacts -> Threshold (rn > 0) -> Cell Data to Point Data -> Extract Surface -> Tube.
import os
import sys


def folder(path):
    """The folder holding bodies.pvd: `path` or its vtk/ subfolder."""
    for d in (path, os.path.join(path, "vtk")):
        if os.path.isfile(os.path.join(d, "bodies.pvd")):
            return d
    raise SystemExit("standard_view: no bodies.pvd in %s nor in %s/vtk" % (path, path))


def band(pv, source, scalar, cut, above):
    """The cells of `source` whose CELLS `scalar` is above `cut` (or at most `cut`)."""
    t = pv.Threshold(Input=source, Scalars=["CELLS", scalar])
    if hasattr(t, "LowerThreshold"):  # ParaView >= 5.10
        t.ThresholdMethod = "Above Upper Threshold" if above else "Below Lower Threshold"
        t.UpperThreshold = t.LowerThreshold = cut
    else:
        t.ThresholdRange = [cut, 1e300] if above else [-1e300, cut]
    return t


def tube_of(pv, source, scalar, radius, vary):
    """source -> (Threshold rn > 0) -> Cell Data to Point Data -> Extract Surface -> Tube."""
    if vary:
        source = band(pv, source, scalar, 1e-12, True)
    lines = pv.ExtractSurface(Input=pv.CellDatatoPointData(Input=source))
    tube = pv.Tube(Input=lines, Radius=radius)
    if vary:
        tube.Scalars = ["POINTS", scalar]
        tube.VaryRadius = "By Scalar"
        tube.RadiusFactor = 4.0
    return tube


def build(pv, d):
    """The standard view of folder `d`; returns the view and the bodies' reader."""
    view = pv.GetActiveViewOrCreate("RenderView")
    view.InteractionMode = "2D"
    view.Background = [1.0, 1.0, 1.0]
    if hasattr(view, "UseColorPaletteForBackground"):  # ParaView >= 5.10: else the palette wins
        view.UseColorPaletteForBackground = 0
    bodies = pv.PVDReader(registrationName="bodies", FileName=os.path.join(d, "bodies.pvd"))
    moving, fixed = band(pv, bodies, "fixed", 0.5, False), band(pv, bodies, "fixed", 0.5, True)
    wrep = pv.Show(fixed, view)
    wrep.ColorArrayName = ["POINTS", ""]  # plain colour
    wrep.AmbientColor = wrep.DiffuseColor = [0.6, 0.6, 0.6]
    rep = pv.Show(moving, view)
    pv.ColorBy(rep, ("CELLS", "velocity", "Magnitude"))
    rep.SetScalarBarVisibility(view, True)
    lut = pv.GetColorTransferFunction("velocity")
    lut.ApplyPreset("Blues", True)
    lut.InvertTransferFunction()  # pale at rest, dark blue fast
    rep.EdgeColor = [0.3, 0.3, 0.3]
    rep.SetRepresentationType("Surface With Edges")
    reps = [rep]
    bounds = bodies.GetDataInformation().GetBounds()
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], 1e-9)
    for name, scalar, preset in (("contacts", "rn", "Inferno (matplotlib)"), ("springs", "rn", "Cool to Warm")):
        path = os.path.join(d, name + ".pvd")
        if not os.path.isfile(path):
            continue
        reader = pv.PVDReader(registrationName=name, FileName=path)
        tube = tube_of(pv, reader, scalar, 1e-3 * size, vary=(name == "contacts"))
        trep = pv.Show(tube, view)
        pv.ColorBy(trep, ("POINTS", scalar))
        trep.SetScalarBarVisibility(view, True)
        pv.GetColorTransferFunction(scalar).ApplyPreset(preset, True)
        reps.append(trep)
    scene = pv.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = (bodies.TimestepValues or [0.0])[-1]
    view.ViewTime = scene.AnimationTime
    for r in reps:  # the colour ranges of the last frame, not of the first (all at rest)
        r.RescaleTransferFunctionToDataRange(False, True)
    pv.ResetCamera(view)
    return view, bodies


def main(argv):
    import argparse
    p = argparse.ArgumentParser(prog="pvbatch standard_view.py", description="The standard view of a run's VTK output.")
    p.add_argument("directory", nargs="?", default=os.environ.get("NSCD_VTK"),
                   help="the run's output folder or its vtk/ (default: $NSCD_VTK)")
    p.add_argument("-o", "--output", help="PNG of the last frame (pvbatch)")
    a = p.parse_args(argv)
    if not a.directory:
        p.error("give the run's output folder (or set NSCD_VTK)")
    try:
        import paraview.simple as pv
    except ImportError as e:
        raise SystemExit("standard_view: ParaView's Python modules are missing (%s): open it with paraview --script=… "
                         "or run it with pvbatch (contrib/paraview/README.md)" % e)
    view, _ = build(pv, folder(a.directory))
    if a.output:
        view.ViewSize = [1200, 800]
        pv.SaveScreenshot(a.output, view)
        print("standard_view: wrote %s" % a.output)
    else:
        pv.Render(view)


# the GUI's --script passes no arguments: NSCD_VTK names the folder
main(sys.argv[1:] if len(sys.argv) > 1 and sys.argv[0].endswith("standard_view.py") else [])
