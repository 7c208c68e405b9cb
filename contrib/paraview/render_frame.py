# contrib/paraview/render_frame.py — renders one frame of nscd's VTK output to a PNG with
# ParaView's pvbatch: the bodies (polygons coloured by |velocity| or |displacement|, fixed bodies
# in grey), the contact force network (a tube per contact point, radius proportional to the
# normal force rn, coloured by rn) and, when the run has PTPT2 links, the sublayer springs
# (lines coloured by their force rn on a diverging map centred on 0).
#
#   xvfb-run -a pvbatch contrib/paraview/render_frame.py OUT_DIR -o frame.png
#   xvfb-run -a pvbatch contrib/paraview/render_frame.py --help
#
# The files and arrays read are those of nscd::VtkWriter (docs/output.md): <P>bodies.pvd,
# <P>contacts.pvd, <P>springs.pvd and their <P><kind>_NNNNNN.vtp frames. The frame is chosen by
# its position in <P>bodies.pvd; the contacts and springs of the same frame are the files with
# the same number NNNNNN (a kind left out of that frame is simply not drawn). Usage notes are in
# contrib/paraview/README.md.
import argparse
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

KINDS = ("bodies", "contacts", "springs")


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="pvbatch render_frame.py",
        description="Render one frame of nscd VTK output (bodies, force network, springs) to a PNG.")
    p.add_argument("directory", help="output directory holding <P>bodies.pvd (or its vtk/ subfolder, as the ballast driver writes)")
    p.add_argument("--prefix", default=None, help="file-name prefix P of the VtkWriter (default: found from the one *bodies.pvd there)")
    p.add_argument("--frame", type=int, default=-1, help="time index in <P>bodies.pvd, from 0; negative counts from the end (default -1: the last)")
    p.add_argument("--time", type=float, default=None, help="instead of --frame: the last frame at or before this simulation time (s)")
    p.add_argument("-o", "--output", default=None, help="PNG file to write (default: <directory>/<P>frame_NNNNNN.png)")
    p.add_argument("--size", type=int, nargs=2, default=[1600, 900], metavar=("W", "H"), help="image size in pixels (default 1600 900)")
    p.add_argument("--bounds", type=float, nargs=4, default=None, metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
                   help="region to show, in m (default: fit to all the bodies)")
    p.add_argument("--color-by", choices=["velocity", "displacement", "none"], default="velocity",
                   help="colour of the moving bodies: magnitude of this cell array, or none (plain) (default velocity)")
    p.add_argument("--range", type=float, nargs=2, default=None, metavar=("MIN", "MAX"),
                   help="colour range of the bodies (default: 0 to the largest magnitude of this frame)")
    p.add_argument("--rn-max", type=float, default=None,
                   help="contact force (N/m) drawn with the full tube radius and the top colour; larger forces are clamped "
                        "(default: the largest rn of this frame; fix it to compare frames)")
    p.add_argument("--rn-min", type=float, default=0.0,
                   help="hide contacts with rn <= this (N/m; default 0: only open contacts are hidden)")
    p.add_argument("--tube-radius", type=float, default=None,
                   help="tube radius (m) of a contact carrying --rn-max (default: 0.15 x the median grain size)")
    p.add_argument("--min-radius", type=float, default=0.1,
                   help="radius of the weakest drawn contact, as a fraction of --tube-radius (default 0.1)")
    p.add_argument("--spring-range", type=float, default=None, metavar="M",
                   help="spring colour range -M..M in N/m (default: the largest |rn| of the springs of this frame)")
    p.add_argument("--spring-width", type=float, default=4.0, help="line width of the springs in pixels (default 4)")
    p.add_argument("--no-contacts", action="store_true", help="do not draw the force network")
    p.add_argument("--no-springs", action="store_true", help="do not draw the springs")
    p.add_argument("--no-edges", action="store_true", help="do not outline the polygons")
    p.add_argument("--no-label", action="store_true", help="no time / frame caption")
    return p.parse_args(argv)


# ---------------------------------------------------------------------------------------------
# Locating the files (plain Python, no ParaView needed)

def find_output(directory, prefix):
    """Returns (dir, prefix) of the bodies collection: in `directory` or in `directory`/vtk."""
    for d in (directory, os.path.join(directory, "vtk")):
        if prefix is not None:
            if os.path.isfile(os.path.join(d, prefix + "bodies.pvd")):
                return d, prefix
            continue
        found = sorted(glob.glob(os.path.join(glob.escape(d), "*bodies.pvd")))
        if len(found) == 1:
            return d, os.path.basename(found[0])[: -len("bodies.pvd")]
        if len(found) > 1:
            names = ", ".join(os.path.basename(f) for f in found)
            sys.exit("render_frame: several collections in %s (%s): choose one with --prefix" % (d, names))
    what = (prefix or "") + "bodies.pvd" if prefix is not None else "*bodies.pvd"
    sys.exit("render_frame: no %s in %s nor in %s" % (what, directory, os.path.join(directory, "vtk")))


def read_pvd(path):
    """The datasets of a .pvd collection as a list of (time, absolute file path), in file order."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        sys.exit("render_frame: cannot read %s: %s" % (path, e))
    base = os.path.dirname(path)
    out = []
    for ds in root.iter("DataSet"):
        out.append((float(ds.get("timestep", "0")), os.path.join(base, ds.get("file"))))
    return out


def frame_number(path):
    """NNNNNN of <P><kind>_NNNNNN.vtp: the VtkWriter frame counter, shared by the three kinds."""
    m = re.search(r"_(\d+)\.vtp$", path)
    return int(m.group(1)) if m else None


def select_frame(bodies, args):
    """Index into the bodies collection chosen by --frame or --time."""
    n = len(bodies)
    if n == 0:
        sys.exit("render_frame: the bodies collection lists no frame")
    if args.time is not None:
        before = [i for i, (t, _) in enumerate(bodies) if t <= args.time]
        if not before:
            sys.exit("render_frame: no frame at or before t = %g s (first at %g s)" % (args.time, bodies[0][0]))
        return before[-1]
    i = args.frame + n if args.frame < 0 else args.frame
    if not 0 <= i < n:
        sys.exit("render_frame: --frame %d out of range: the collection has %d frames (0..%d)" % (args.frame, n, n - 1))
    return i


def matching_file(directory, prefix, kind, number):
    """The <kind> file of the same frame number, if that frame wrote one and the collection lists it."""
    pvd = os.path.join(directory, prefix + kind + ".pvd")
    if number is None or not os.path.isfile(pvd):
        return None
    for _, f in read_pvd(pvd):
        if frame_number(f) == number and os.path.isfile(f):
            return f
    return None


# ---------------------------------------------------------------------------------------------
# Small data queries on the fetched polydata (the files are small: a few thousand cells)

def grain_size(poly):
    """Median over the cells of the larger side of the cell's bounding box (m): the grain scale."""
    sizes = []
    for c in range(poly.GetNumberOfCells()):
        b = poly.GetCell(c).GetBounds()
        sizes.append(max(b[1] - b[0], b[3] - b[2]))
    sizes.sort()
    return sizes[len(sizes) // 2] if sizes else 0.0


def max_magnitude(poly, name):
    arr = poly.GetCellData().GetArray(name)
    if arr is None or arr.GetNumberOfTuples() == 0:
        return 0.0
    return arr.GetRange(-1)[1]  # component -1: the range of the vector magnitude


def max_abs(poly, name):
    arr = poly.GetCellData().GetArray(name)
    if arr is None or arr.GetNumberOfTuples() == 0:
        return 0.0
    lo, hi = arr.GetRange(0)
    return max(abs(lo), abs(hi))


# ---------------------------------------------------------------------------------------------
# Rendering

def set_threshold(filt, array, lo, hi):
    """Keeps the cells with lo <= array <= hi (the property names changed in ParaView 5.10)."""
    filt.Scalars = ["CELLS", array]
    if hasattr(filt, "LowerThreshold"):
        filt.LowerThreshold, filt.UpperThreshold = lo, hi
        filt.ThresholdMethod = "Between"
    else:
        filt.ThresholdRange = [lo, hi]


STRIP_PX = 250  # width of the right-hand strip that holds the colour bars, in pixels


def style_bar(pv, lut, view, title, slot, n_slots, size):
    """A vertical colour bar in the right-hand strip; `slot` counts from the top."""
    w, h = size
    top = 1.0 - 75.0 / h  # below the caption
    bottom = 25.0 / h
    height = (top - bottom) / n_slots
    bar = pv.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.Orientation = "Vertical"
    bar.WindowLocation = "Any Location"
    bar.ScalarBarLength = 0.75 * height
    # x: the bar a little left of the strip's middle (its tick labels go to its right); the
    # title is centred on the bar.
    bar.Position = [1.0 - 0.55 * STRIP_PX / w, top - (slot + 1) * height + 0.05 * height]
    bar.HorizontalTitle = 1
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.TitleFontSize = 18
    bar.LabelFontSize = 15
    bar.ScalarBarThickness = 18
    bar.RangeLabelFormat = "%.3g"
    bar.AddRangeLabels = 1
    bar.DrawTickLabels = 1
    bar.Visibility = 1
    return bar


def render(args):
    directory, prefix = find_output(args.directory, args.prefix)
    bodies = read_pvd(os.path.join(directory, prefix + "bodies.pvd"))
    index = select_frame(bodies, args)
    time, bodies_file = bodies[index]
    number = frame_number(bodies_file)
    contacts_file = None if args.no_contacts else matching_file(directory, prefix, "contacts", number)
    springs_file = None if args.no_springs else matching_file(directory, prefix, "springs", number)
    output = args.output or os.path.join(directory, "%sframe_%06d.png" % (prefix, number if number is not None else index))

    try:
        import paraview.simple as pv
        from paraview import servermanager as sm
    except ImportError as e:
        sys.exit("render_frame: ParaView's Python modules are missing (%s): run this script with pvbatch or "
                 "pvpython, and see contrib/paraview/README.md for Debian's python3-paraview" % e)

    view = pv.CreateView("RenderView")
    view.ViewSize = list(args.size)
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.CameraParallelProjection = 1
    if hasattr(view, "UseFXAA"):
        view.UseFXAA = 1  # anti-aliased polygon edges and thin tubes
    pv.SetActiveView(view)

    # --- bodies: moving ones coloured, fixed ones (walls, floor) grey --------------------------
    body_reader = pv.XMLPolyDataReader(FileName=[bodies_file])
    body_reader.UpdatePipeline()
    body_data = sm.Fetch(body_reader)
    bb = body_data.GetBounds()
    moving = pv.Threshold(Input=body_reader)
    set_threshold(moving, "fixed", -0.5, 0.5)
    fixed = pv.Threshold(Input=body_reader)
    set_threshold(fixed, "fixed", 0.5, 1.5)
    moving.UpdatePipeline()
    moving_data = sm.Fetch(moving)
    d_grain = grain_size(moving_data) or 0.02 * max(bb[1] - bb[0], bb[3] - bb[2])

    z_top = 2.0 * d_grain  # above everything drawn (the bodies lie at z = 0)
    edges = not args.no_edges
    bars = []  # (lut, title), top to bottom
    for src, is_fixed in ((fixed, True), (moving, False)):
        rep = pv.Show(src, view)
        rep.SetRepresentationType("Surface With Edges" if edges else "Surface")
        rep.EdgeColor = [0.25, 0.25, 0.25]
        rep.LineWidth = 1.0
        rep.Ambient, rep.Diffuse, rep.Specular = 1.0, 0.0, 0.0  # flat 2D: the colours as given
        if is_fixed or args.color_by == "none":
            rep.ColorArrayName = ["POINTS", ""]  # solid colour
            rep.AmbientColor = rep.DiffuseColor = [0.72, 0.72, 0.72] if is_fixed else [0.85, 0.80, 0.68]
            continue
        pv.ColorBy(rep, ("CELLS", args.color_by, "Magnitude"))
        lut = pv.GetColorTransferFunction(args.color_by)
        # Pale grey (at rest) to steel blue (fastest): light grains, so the chains read over them.
        lut.RGBPoints = [0.0, 0.93, 0.93, 0.93, 1.0, 0.22, 0.42, 0.72]
        lut.ColorSpace = "Lab"
        lut.VectorMode = "Magnitude"
        lut.AutomaticRescaleRangeMode = "Never"
        lo, hi = args.range if args.range else (0.0, max_magnitude(moving_data, args.color_by))
        if not hi > lo:  # e.g. everything at rest: a unit range rather than a degenerate one
            hi = lo + 1.0
        lut.RescaleTransferFunction(lo, hi)
        pv.GetOpacityTransferFunction(args.color_by).RescaleTransferFunction(lo, hi)
        bars.append((lut, "speed (m/s)" if args.color_by == "velocity" else "displacement (m)"))

    # --- force network: a tube per contact point, radius proportional to rn --------------------
    n_active, n_contacts, rn_top = 0, 0, 0.0
    if contacts_file:
        c_reader = pv.XMLPolyDataReader(FileName=[contacts_file])
        c_reader.UpdatePipeline()
        c_data = sm.Fetch(c_reader)
        n_contacts = c_data.GetNumberOfCells()
        rn_arr = c_data.GetCellData().GetArray("rn")
        rn_frame = rn_arr.GetRange(0)[1] if rn_arr is not None and rn_arr.GetNumberOfTuples() > 0 else 0.0
        rn_top = args.rn_max if args.rn_max else rn_frame
        if rn_top > 0.0 and rn_frame > args.rn_min:
            active = pv.Threshold(Input=c_reader)
            # rn > rn_min: the open contacts (rn = 0) carry nothing and are not drawn.
            set_threshold(active, "rn", args.rn_min + 1e-12 * rn_top, max(rn_frame, rn_top) * 2.0)
            active.UpdatePipeline()
            n_active = active.GetDataInformation().GetNumberOfCells()
            radius = args.tube_radius if args.tube_radius else 0.15 * d_grain
            # Radius r = R (f + (1 - f) min(rn / rn_max, 1)): a chain's width reads as its force,
            # and the floor f R keeps the weak contacts (grains resting under their own weight)
            # visible as hairlines.
            f = min(max(args.min_radius, 0.0), 1.0)
            calc = pv.Calculator(Input=active)
            calc.AttributeType = "Cell Data"
            calc.ResultArrayName = "tube_radius"
            calc.Function = "%.17g*(%.17g+%.17g*min(rn/%.17g,1))" % (radius, f, 1.0 - f, rn_top)
            # Tube needs point data; each segment owns its two points, so the conversion keeps
            # every contact's values unchanged.
            points = pv.CellDatatoPointData(Input=calc)
            lines = pv.ExtractSurface(Input=points)  # Threshold made an unstructured grid
            tube = pv.Tube(Input=lines)
            tube.Scalars = ["POINTS", "tube_radius"]
            tube.VaryRadius = "By Absolute Scalar"
            tube.NumberofSides = 12
            tube.Capping = 1
            rep = pv.Show(tube, view)
            pv.ColorBy(rep, ("POINTS", "rn"))
            rep.Specular = 0.3
            rep.Position = [0.0, 0.0, 3.0 * radius]  # above the polygons and their edges
            z_top = max(z_top, 5.0 * radius)
            lut = pv.GetColorTransferFunction("rn")
            # Amber (weak) through red to dark maroon (strong): no end of the map fades into the
            # pale grains or the white background.
            lut.RGBPoints = [0.0, 1.0, 0.72, 0.0, 0.5, 0.86, 0.10, 0.05, 1.0, 0.22, 0.0, 0.02]
            lut.ColorSpace = "Lab"
            lut.AutomaticRescaleRangeMode = "Never"
            lut.RescaleTransferFunction(0.0, rn_top)
            bars.append((lut, "contact rn (N/m)"))

    # --- sublayer springs: lines coloured by their force --------------------------------------
    n_springs = 0
    if springs_file:
        s_reader = pv.XMLPolyDataReader(FileName=[springs_file])
        s_reader.UpdatePipeline()
        s_data = sm.Fetch(s_reader)
        n_springs = s_data.GetNumberOfCells()
        if n_springs > 0:
            # Its own array name, so that the springs get their own colour map, not the contacts'.
            calc = pv.Calculator(Input=s_reader)
            calc.AttributeType = "Cell Data"
            calc.ResultArrayName = "spring_rn"
            calc.Function = "rn"
            rep = pv.Show(calc, view)
            rep.SetRepresentationType("Surface")
            rep.LineWidth = args.spring_width
            rep.RenderLinesAsTubes = 1
            rep.Position = [0.0, 0.0, 0.5 * d_grain]
            pv.ColorBy(rep, ("CELLS", "spring_rn"))
            lut = pv.GetColorTransferFunction("spring_rn")
            lut.ApplyPreset("Cool to Warm", True)  # diverging: blue pulls (rn < 0), red pushes
            lut.AutomaticRescaleRangeMode = "Never"
            m = args.spring_range if args.spring_range else max_abs(s_data, "rn")
            m = m if m > 0.0 else 1.0
            lut.RescaleTransferFunction(-m, m)
            bars.append((lut, "spring rn (N/m)"))

    for slot, (lut, title) in enumerate(bars):
        style_bar(pv, lut, view, title, slot, max(len(bars), 2), args.size)

    # --- caption -----------------------------------------------------------------------------
    if not args.no_label:
        text = "t = %.5g s   frame %d (of 0..%d)" % (time, index, len(bodies) - 1)
        if contacts_file and n_active > 0:
            text += "\n%d loaded contacts, max rn %.4g N/m" % (n_active, rn_top)
        elif contacts_file:
            text += "\n%d contacts, none loaded (rn = 0)" % n_contacts
        elif not args.no_contacts:
            text += "\nno contacts file for this frame"
        if springs_file:
            text += "\n%d springs" % n_springs
        label = pv.Text(Text=text)
        lrep = pv.Show(label, view)
        lrep.WindowLocation = "Upper Right Corner"
        lrep.Justification = "Right"
        lrep.Color = [0.0, 0.0, 0.0]
        lrep.FontSize = 14

    # --- camera: parallel projection on the region, leaving the right strip to the bars -------
    if args.bounds:
        x0, x1, y0, y1 = args.bounds
    else:
        x0, x1, y0, y1 = bb[0], bb[1], bb[2], bb[3]
    if not (x1 > x0 and y1 > y0):
        sys.exit("render_frame: empty view bounds (%g %g %g %g)" % (x0, x1, y0, y1))
    w, h = args.size
    strip = min(STRIP_PX / w, 0.5) if bars else 0.0  # fraction of the width kept for the bars
    aspect = w * (1.0 - strip) / h         # aspect of the drawing area
    margin = 1.04
    half_h = margin * max(0.5 * (y1 - y0), 0.5 * (x1 - x0) / aspect)  # parallel scale
    cx = 0.5 * (x0 + x1) + half_h * (w / h) * strip  # shift right: the data sits left of the strip
    cy = 0.5 * (y0 + y1)
    if bars:
        # A white panel over the strip, above everything drawn, so that bodies outside the view
        # bounds (or the region's own overhang) never run under the colour bars.
        half_w = half_h * w / h
        panel = pv.Plane(Origin=[cx + half_w * (1.0 - 2.0 * strip), cy - 2.0 * half_h, z_top],
                         Point1=[cx + 2.0 * half_w, cy - 2.0 * half_h, z_top],
                         Point2=[cx + half_w * (1.0 - 2.0 * strip), cy + 2.0 * half_h, z_top])
        prep = pv.Show(panel, view)
        prep.ColorArrayName = ["POINTS", ""]
        prep.AmbientColor = prep.DiffuseColor = [1.0, 1.0, 1.0]
        prep.Ambient, prep.Diffuse, prep.Specular = 1.0, 0.0, 0.0
    pv.Render(view)
    view.CameraFocalPoint = [cx, cy, 0.0]
    view.CameraPosition = [cx, cy, 2.0 * z_top + 10.0 * max(x1 - x0, y1 - y0)]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = half_h
    pv.Render(view)
    out_dir = os.path.dirname(os.path.abspath(output))
    os.makedirs(out_dir, exist_ok=True)
    pv.SaveScreenshot(output, view, ImageResolution=list(args.size), TransparentBackground=0)
    print("render_frame: frame %d (t = %.6g s) of %s -> %s" % (index, time, os.path.join(directory, prefix + "bodies.pvd"), output))


if __name__ == "__main__":
    render(parse_args(sys.argv[1:]))
