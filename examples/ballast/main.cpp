// examples/ballast/main.cpp — `ballast`: the ballast settlement study, nscd's main job
// (Saussine et al. 2006, §2.9, §3, §4).
//
// What it shows
//   A 2D layer of graded pentagons (361/242/121 of 1/1.5/2 cm, ρ = 2367 kg/m³, μ = 0.5, e = 0)
//   between a sleeper and a visco-elastic sublayer (pads on springs k_N = 4100 N/m,
//   ν = 80 N·s/m), loaded by F = A + B cos(2π f t − φ) (A = −1000 N/m, B = −500 N/m per metre of thickness, f = 20 Hz,
//   φ = −π) for many cycles: the sleeper's settlement, cycle after cycle, and what each cycle
//   cost (sweeps, time) and got (overlaps).
//
// Build
//   cmake -S . -B build && cmake --build build --target ballast
// Run
//   build/examples/ballast/ballast                          (prepare a sample, 30 cycles, minutes)
//   build/examples/ballast/ballast --cycles 1000 --sample out/ballast/sample.nscd --output out/b1000
//   build/examples/ballast/ballast --resume out/b1000 --cycles 2000   (continue a killed or finished run)
//   build/examples/ballast/ballast --help                   (every option, units, defaults)
// Outputs under --output (default out/ballast)
//   sample.nscd      the prepared sample (deposit + sleeper), reusable with --sample
//   cycles.csv       per cycle: settlement at the smallest and largest load, lateral displacement,
//                    mean grain speed, mean/max overlap, mean sweeps, wall time
//   steps.csv        every --steps-every steps: load, settlement, contacts, sweeps, criteria, overlaps
//   vtk/             bodies, contacts (force network) and springs (sublayer) for ParaView
//   checkpoint.nscd  every --checkpoint-every cycles and at the end (for --resume)
//   summary.txt      key = value: final_settlement (m), cycles, wall_time (s), time_per_cycle (s),
//                    mean_sweeps, max_overlap (m), ...
// Steps: see ballast_study.cpp (1. sample, 2. load, 3. cycles, 4. summary).
#include "ballast_study.hpp"
#include "nscd/shared/driver/run_main.hpp"

// Exit status (nscd::driver::run_main): 0 done, 2 bad input (options, sample, checkpoint),
// 1 an error during the run, 3 a physically impossible result, 143 stopped by SIGTERM after
// saving its checkpoint.
int main(int argc, char** argv) { return nscd::driver::run_main("ballast", argc, argv, ballast::Config{}, ballast::parse, ballast::run); }
