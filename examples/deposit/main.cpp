// examples/deposit/main.cpp — `deposit`: the paper's ballast sample falls under gravity and
// settles (Saussine et al. 2006, §3: 361/242/121 pentagons of 1/1.5/2 cm, ρ = 2367 kg/m³,
// μ = 0.5, e = 0).
//
// What it shows
//   The Moreau–Jean θ-method with Signorini–Coulomb contacts solved by NLGS on a real
//   granular deposit: what each step costs (sweeps, detection and solver time) and what it
//   gets (convergence criteria, overlaps), until the grains are at rest.
//
// Build
//   cmake -S . -B build && cmake --build build --target deposit
// Run
//   build/examples/deposit/deposit                                  (defaults: paper values)
//   build/examples/deposit/deposit --config examples/deposit/deposit.cfg
//   build/examples/deposit/deposit --grains 7000                    (the grading scaled, box 9.67 m)
//   build/examples/deposit/deposit --help                           (every option)
// Outputs under --output (default out/deposit)
//   steps.csv        one row per step: contacts, sweeps, criteria, overlaps, rms speed, times
//   summary.txt      key = value: packing_fraction, coordination_number, double_contact_share,
//                    mean_overlap, max_overlap (m), steps, wall_time (s), mean_sweeps, ...
//   vtk/             bodies and contacts frames for ParaView (bodies.pvd, contacts.pvd)
//   final_state.nscd the settled sample (nscd checkpoint: nscd::load_checkpoint reloads it)
//
// Steps (deposit_study.cpp): 1. scene  2. time stepping, law, solver  3. steps to equilibrium
// with progress and ETA  4. summary and final state.
#include "deposit_study.hpp"
#include "nscd/shared/driver/run_main.hpp"

// Exit status (nscd::driver::run_main): 0 done, 2 bad input, 1 an error during the run, 3 a
// physically impossible result.
int main(int argc, char** argv) {
  auto parse = [](int ac, char** av, deposit::Config& c) {
    return deposit::parse(ac, av, c, "deposit", "the paper's pentagon sample settling under gravity");
  };
  return nscd::driver::run_main("deposit", argc, argv, deposit::Config{}, parse, deposit::run);
}
