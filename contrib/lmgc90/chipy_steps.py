"""contrib/lmgc90/chipy_steps.py -- the chipy command loop shared by deposit_700.py and
run_datbox.py: the start of a rigid 2D run, one time step with its NLGS loop spelled out (as
ExSolver does it: check_every sweeps, then a check) so that its sweeps can be counted, and the
per-step measure of the interactions.
"""


def start(chipy, dt, theta):
    """Initializes chipy and reads the DATBOX folder of the working directory (rigid bodies, 2D)."""
    chipy.Initialize()
    chipy.checkDirectories()
    chipy.utilities_DisableLogMes()
    chipy.SetDimension(2)
    chipy.TimeEvolution_SetTimeStep(dt)
    chipy.Integrator_InitTheta(theta)
    chipy.ReadDatbox(deformable=False)
    chipy.ComputeMass()


def solve(chipy, norm, tol, relax, check_every, max_checks):
    """One NLGS solve (Stored_Delassus_Loops): at most max_checks rounds of check_every sweeps
    and a check (one more sweep, not counted by LMGC90). Returns (sweeps, checks, status), status
    the last nlgs_AfterIterCheck (0: converged, -1: stopped, 1: not converged)."""
    chipy.nlgs_SetCheckType(norm, tol, relax)
    chipy.nlgs_ExPrep('Stored_Delassus_Loops')
    sweeps, checks, status = 0, 0, 1
    for _ in range(max_checks):
        chipy.nlgs_ExIter(check_every)
        sweeps += check_every
        status = chipy.nlgs_AfterIterCheck()
        checks += 1
        if status in (0, -1):
            break
    chipy.nlgs_ExPost()
    return sweeps, checks, status


def step(chipy, norm, tol, relax, check_every, max_checks):
    """One time step, its contact forces from solve(); returns what solve() returns."""
    chipy.IncrementStep()
    chipy.ComputeFext()
    chipy.ComputeBulk()
    chipy.ComputeFreeVelocity()
    chipy.SelectProxTactors()
    chipy.RecupRloc()
    r = solve(chipy, norm, tol, relax, check_every, max_checks)
    chipy.StockRloc()
    chipy.ComputeDof()
    chipy.UpdateStep()
    return r


def measure(chipy, numpy):
    """(interactions, those with a non-zero force, the largest overlap -gapTT, >= 0)."""
    inters = chipy.getInteractions(this=True, human=False)
    if not len(inters):
        return 0, 0, 0.0
    active = int(numpy.count_nonzero(numpy.any(inters['rl'] != 0.0, axis=1)))
    return len(inters), active, float(max(0.0, -inters['gapTT'].min()))
