// tools/fuzz/fuzz_datbox.cpp — an LMGC90 DATBOX folder (issue #39) as read_datbox reads it. The
// input is the folder's files one after the other, each opened by a line "#FILE <name>"
// (BODIES.DAT, BULK_BEHAV.DAT, TACT_BEHAV.DAT, DRV_DOF.DAT, DOF.INI, Vloc_Rloc.INI, an evolution
// file); run.sh makes the seeds so from tests/data/datbox/*. Reading may refuse (nscd::Error); a
// folder that reads must be written back (write_datbox, which may refuse what a DATBOX cannot
// hold: nscd::Error), read again, and step 3 times without a crash or a sanitizer report.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fuzz_support.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/datbox.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path dir = fuzz::scratch("_datbox"), back = fuzz::scratch("_datbox_back");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::istringstream in(fuzz::text(data, size));
  std::ofstream out;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#FILE ", 0) == 0) {
      const std::string name = line.substr(6);
      if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") return 0;
      out.close();
      out.open(dir / name, std::ios::binary | std::ios::trunc);
    } else if (out.is_open()) {
      out << line << '\n';
    }
  }
  out.close();
  try {
    nscd::Datbox d = nscd::read_datbox(dir);
    if (d.reg.bodies.size() > 200) return 0;  // keep each input fast
    nscd::DatboxExtras x;
    x.law_name = &d.law_name;
    x.drives = &d.drives;
    x.contacts = &d.contacts;
    fs::remove_all(back);
    try {
      nscd::write_datbox(back, d.reg, x);
    } catch (const nscd::Error&) {
      return 0;
    }
    nscd::Datbox again = nscd::read_datbox(back);  // what was written must read: an Error here is a finding
    if (again.reg.bodies.size() != d.reg.bodies.size()) __builtin_trap();
    d.reg.params.dt = 1e-3;
    nscd::StepperOptions o;
    o.nlgs.max_sweeps = 50;
    nscd::MoreauJean mj(d.reg, o);
    for (int i = 0; i < 3; ++i) mj.step();
  } catch (const nscd::Error&) {
  }
  return 0;
}
