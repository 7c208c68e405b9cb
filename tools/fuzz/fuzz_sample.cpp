// tools/fuzz/fuzz_sample.cpp — a ballast sample or run checkpoint as `ballast --sample` and
// `--resume` use it: load it, read its stored options (from_map, then check: refusals are
// std::invalid_argument), recognise the ballast scene, set the warm start, change the sublayer
// stiffness and step a few times. Loading may refuse (nscd::Error); a sample that loads must
// step without a crash or a sanitizer report (the issue's `w inf` sample segfaulted).
#include <cmath>
#include <stdexcept>

#include "ballast_study.hpp"

#include "fuzz_support.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/solvers/moreau_jean.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    nscd::Checkpoint cp = nscd::load_checkpoint_text(fuzz::text(data, size), "fuzz.nscd");
    try {
      ballast::Config c;
      ballast::from_map(cp.extra, c, "fuzz.nscd");
      c.prepare_only = true;  // (cycles may be anything here)
      ballast::check(c);
    } catch (const std::invalid_argument&) {
    }
    if (cp.reg.bodies.size() > 400) return 0;  // keep each input fast
    nscd::scenes::BallastScene s = nscd::scenes::recognise_ballast(std::move(cp.reg));
    if (!s.sleeper.valid()) return 0;
    nscd::Registry& reg = s.scene.reg;
    reg.params.dt = 2e-4;  // as ballast does: the run's own step and alert
    reg.params.alert = 1.25e-3;
    reg.params.theta = 0.5;
    nscd::scenes::scale_sublayer_stiffness(s, 2.0);
    nscd::StepperOptions o;
    o.nlgs.max_sweeps = 50;
    nscd::MoreauJean mj(reg, o);
    mj.set_warm_start_memory(cp.warm_start);
    for (int i = 0; i < 3; ++i) mj.step();
  } catch (const nscd::Error&) {
  }
  return 0;
}
