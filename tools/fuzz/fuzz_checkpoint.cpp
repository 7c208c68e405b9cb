// tools/fuzz/fuzz_checkpoint.cpp — nscd::load_checkpoint (checkpoints and samples): any input
// either loads or throws nscd::Error; anything else (a crash, a sanitizer report, another
// exception type) is a finding. A state that loads must also save (save refuses exactly what
// load refuses).
#include "fuzz_support.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nscd::Checkpoint cp;
  try {
    cp = nscd::load_checkpoint_text(fuzz::text(data, size), "fuzz.nscd");
  } catch (const nscd::Error&) {
    return 0;
  }
  // what loaded saves again (to a file of this process)
  nscd::save_checkpoint(fuzz::scratch(".nscd"), cp.reg, cp.warm_start, cp.extra);
  return 0;
}
