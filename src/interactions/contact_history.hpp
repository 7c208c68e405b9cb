// nscd/interactions/contact_history.hpp — what a contact remembers from one step to the next:
// its force, keyed by the contactor pair and the touching features (the warm-start memory).
//
// It belongs to the interactions, not to a solver: any solver starts from it (NLGS applies
// it before sweeping, NEWTON_AC takes it as its first iterate), the stepper refreshes it at
// the end of every step, and checkpoints save it so that a resumed run continues bit for bit.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nscd/core/ids.hpp"

namespace nscd {

/// One remembered contact: forces (N per unit thickness) of the pair's contact at `feature`.
struct ContactMemory {
  std::uint64_t pair = 0;     ///< candidate ContactorId << 32 | antagonist ContactorId
  std::uint32_t feature = 0;  ///< which vertices / edges touch (ContactTable::feature)
  double rn = 0.0, rt = 0.0;
  bool operator<(const ContactMemory& o) const { return pair != o.pair ? pair < o.pair : feature < o.feature; }
};

/// The memory of a whole step; sorted by (pair, feature) where it is handed out and saved
/// (MoreauJean::warm_start_memory, checkpoints), found by ContactHistoryIndex in any order.
using ContactHistory = std::vector<ContactMemory>;

/// A hash index over a ContactHistory: the entry of a (pair, feature), found in one or two
/// probes where a binary search takes a dozen mispredicted branches (the warm start looks up
/// every contact of every step, and the binary search dominated MoreauJean::prepare:
/// docs/benchmarks.md §8). Open addressing, linear probing, at most half full; built from the history
/// in its order, the first of equal keys wins, as std::lower_bound would find it.
class ContactHistoryIndex {
 public:
  /// Indexes `h`; the lookups take the same history, unchanged since. On `threads` threads the
  /// keys go in at once, each slot taken by a compare-and-swap and an equal key's slot lowered to
  /// the smaller entry: the slots differ from one build to the next, the answers do not.
  void build(const ContactHistory& h, int threads = 1);
  /// The entry of (pair, feature) in `h` (the history built from), or nullptr.
  const ContactMemory* find(const ContactHistory& h, std::uint64_t pair, std::uint32_t feature) const {
    const std::uint32_t k = find_index(h, pair, feature);
    return k == kNone ? nullptr : &h[k];
  }

  /// No entry (find_range's answer).
  static constexpr std::uint32_t kNone = 0xffffffffu;
  /// A history smaller than this stays in a core's L2 cache from one step to the next (half the
  /// L2 of the machine of docs/benchmarks.md §8): find_range then looks up without prefetching.
  static constexpr std::size_t kCachedBytes = std::size_t{512} << 10;

  /// The entries of the keys `key(i)` = {pair, feature}, i in [begin, end): found(i, k) with
  /// their index k in `h`, or kNone; the same answers as find, one key after the other, but the
  /// table's slot and the entry of the keys `kAhead` and 2·`kAhead` further on are prefetched
  /// meanwhile, so that the misses of several keys overlap (a large history is out of the
  /// caches: at 70,000 grains its lookups, one miss after the other, took half of the samples
  /// `perf` gave MoreauJean::prepare itself, the colouring aside). A history of less
  /// than kCachedBytes is looked up key by key.
  template <class Key, class Found>
  void find_range(const ContactHistory& h, std::size_t begin, std::size_t end, Key key, Found found) const {
    if (slots_.empty() || h.size() * sizeof(ContactMemory) < kCachedBytes) {  // no prefetch: it would only cost
      for (std::size_t i = begin; i < end; ++i) {
        const auto [pair, feature] = key(i);
        found(i, find_index(h, pair, feature));
      }
      return;
    }
    // each key's slot computed once, 2·kAhead keys ahead, and kept in a ring until its lookup
    constexpr std::size_t kAhead = 8, kRing = 4 * kAhead;
    struct Pending {
      std::uint64_t pair;
      std::uint32_t feature;
      std::size_t slot;
    } ring[kRing];
    auto enqueue = [&](std::size_t i) {
      const auto [pair, feature] = key(i);
      Pending& p = ring[i % kRing];
      p = {pair, feature, slot(pair, feature)};
      __builtin_prefetch(&slots_[p.slot]);
    };
    for (std::size_t i = begin; i < std::min(end, begin + 2 * kAhead); ++i) enqueue(i);
    for (std::size_t i = begin; i < end; ++i) {
      if (i + 2 * kAhead < end) enqueue(i + 2 * kAhead);
      if (i + kAhead < end) {
        const std::uint32_t k = slots_[ring[(i + kAhead) % kRing].slot];  // its line was prefetched a while ago
        if (k != kEmpty) __builtin_prefetch(&h[k]);
      }
      const Pending& p = ring[i % kRing];
      found(i, probe(h, p.slot, p.pair, p.feature));
    }
  }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  std::uint32_t find_index(const ContactHistory& h, std::uint64_t pair, std::uint32_t feature) const {
    return slots_.empty() ? kNone : probe(h, slot(pair, feature), pair, feature);
  }
  std::uint32_t probe(const ContactHistory& h, std::size_t first, std::uint64_t pair, std::uint32_t feature) const {
    for (std::size_t s = first;; s = (s + 1) & mask_) {
      if (slots_[s] == kEmpty) return kNone;
      if (same(h, slots_[s], pair, feature)) return slots_[s];
    }
  }
  void insert(const ContactHistory& h, std::uint32_t k);
  void insert_shared(const ContactHistory& h, std::uint32_t k);
  std::size_t slot(std::uint64_t pair, std::uint32_t feature) const {
    const std::uint64_t k = (pair ^ (std::uint64_t{feature} * 0x9E3779B97F4A7C15ull)) * 0xD6E8FEB86659FD93ull;
    return static_cast<std::size_t>(k >> 32) & mask_;
  }
  static bool same(const ContactHistory& h, std::uint32_t k, std::uint64_t pair, std::uint32_t feature) {
    return h[k].pair == pair && h[k].feature == feature;
  }
  std::vector<std::uint32_t> slots_;
  std::size_t mask_ = 0;
};

inline std::uint64_t contact_pair_key(ContactorId candidate, ContactorId antagonist) {
  return (std::uint64_t(candidate.value) << 32) | antagonist.value;
}

}  // namespace nscd
