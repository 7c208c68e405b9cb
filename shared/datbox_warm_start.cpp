// nscd/shared/datbox_warm_start.cpp — see datbox_warm_start.hpp.
#include "nscd/shared/datbox_warm_start.hpp"

#include <algorithm>
#include <limits>

#include "nscd/solvers/moreau_jean.hpp"

namespace nscd::scenes {

ContactHistory datbox_warm_start(const Registry& reg, std::span<const DatboxContact> contacts, std::size_t* matched) {
  Registry copy = reg;
  MoreauJean mj(copy);
  mj.begin_step();
  mj.detect();
  const ContactTable& t = copy.contacts;
  ContactHistory h;
  for (const DatboxContact& c : contacts) {
    std::size_t best = t.size();
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < t.size(); ++i) {
      const bool same = (t.candidate[i] == c.cd && t.antagonist[i] == c.an) || (t.candidate[i] == c.an && t.antagonist[i] == c.cd);
      if (!same) continue;
      const Vec2 d = t.point[i] - c.point;
      if (dot(d, d) < best_d) {
        best_d = dot(d, d);
        best = i;
      }
    }
    if (best == t.size()) continue;
    // swapping candidate and antagonist reverses n, t and the force: rn, rt are unchanged
    h.push_back({(std::uint64_t(t.candidate[best].value) << 32) | t.antagonist[best].value, t.feature[best], c.rln, c.rlt});
  }
  std::sort(h.begin(), h.end());
  h.erase(std::unique(h.begin(), h.end(), [](const ContactMemory& a, const ContactMemory& b) { return !(a < b) && !(b < a); }), h.end());
  if (matched) *matched = h.size();
  return h;
}

}  // namespace nscd::scenes
