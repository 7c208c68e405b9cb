// nscd/interactions/contact_history.cpp — ContactHistoryIndex's build (contact_history.hpp), on
// one thread or on several.
#include "nscd/interactions/contact_history.hpp"

#include <atomic>

namespace nscd {

void ContactHistoryIndex::build(const ContactHistory& h, int threads) {
  std::size_t size = 16;
  while (size < 2 * h.size()) size *= 2;
  mask_ = size - 1;
  if (threads <= 1) {
    slots_.assign(size, kEmpty);
    for (std::uint32_t k = 0; k < h.size(); ++k) insert(h, k);
    return;
  }
  slots_.resize(size);
  const auto n = static_cast<std::ptrdiff_t>(h.size()), m = static_cast<std::ptrdiff_t>(size);
#pragma omp parallel num_threads(threads)
  {
#pragma omp for schedule(static)
    for (std::ptrdiff_t s = 0; s < m; ++s) slots_[static_cast<std::size_t>(s)] = kEmpty;
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < n; ++k) insert_shared(h, static_cast<std::uint32_t>(k));
  }
}

// The first of equal keys wins by coming first.
void ContactHistoryIndex::insert(const ContactHistory& h, std::uint32_t k) {
  std::size_t s = slot(h[k].pair, h[k].feature);
  while (slots_[s] != kEmpty && !same(h, slots_[s], h[k].pair, h[k].feature)) s = (s + 1) & mask_;
  if (slots_[s] == kEmpty) slots_[s] = k;
}

// Among threads, the first of equal keys wins by its smaller k: a slot only ever goes from empty
// to an entry of one key, then to smaller entries of that key, so a key never takes two slots
// and the last value of its slot is its smallest entry, whatever the threads' interleaving.
void ContactHistoryIndex::insert_shared(const ContactHistory& h, std::uint32_t k) {
  for (std::size_t s = slot(h[k].pair, h[k].feature);; s = (s + 1) & mask_) {
    std::atomic_ref<std::uint32_t> cell(slots_[s]);
    std::uint32_t j = cell.load(std::memory_order_relaxed);
    while (j == kEmpty && !cell.compare_exchange_weak(j, k, std::memory_order_relaxed)) {
    }
    if (j == kEmpty) return;  // taken
    if (!same(h, j, h[k].pair, h[k].feature)) continue;
    while (j > k && !cell.compare_exchange_weak(j, k, std::memory_order_relaxed)) {
    }
    return;
  }
}

}  // namespace nscd
