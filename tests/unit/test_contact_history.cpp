// tests/unit/test_contact_history.cpp — ContactHistoryIndex (interactions/contact_history.hpp),
// the hash index the warm start looks contacts up in: it must find exactly what a binary search
// of the sorted history finds (the entry of a (pair, feature), the first of equal keys), and
// nothing for a key the history lacks, so that the warm start gives the same bits as before.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "nscd/interactions/contact_history.hpp"

namespace nscd {
namespace {

/// What the warm start found before the index: std::lower_bound over the sorted history.
const ContactMemory* binary_search(const ContactHistory& h, std::uint64_t pair, std::uint32_t feature) {
  const ContactMemory key{pair, feature, 0.0, 0.0};
  const auto it = std::lower_bound(h.begin(), h.end(), key);
  return it == h.end() || it->pair != pair || it->feature != feature ? nullptr : &*it;
}

/// A step's memory: `n` contacts of polygon pairs among `polygons`, 1 or 2 features each.
ContactHistory random_history(std::size_t n, std::uint32_t polygons, std::mt19937& rng) {
  std::uniform_int_distribution<std::uint32_t> polygon(0, polygons - 1), edge(0, 4), kind(1, 3);
  ContactHistory h;
  while (h.size() < n) {
    const std::uint32_t a = polygon(rng), b = polygon(rng);
    if (a == b) continue;
    const std::uint64_t pair = std::uint64_t{std::max(a, b)} << 32 | std::min(a, b);
    const std::uint32_t feature = kind(rng) << 30 | edge(rng) << 12 | edge(rng);
    h.push_back({pair, feature, 1.0 * h.size(), -0.5});
    if (kind(rng) == 3) h.push_back({pair, feature | 1u << 24, 2.0, 0.0});  // the second point of an edge–edge pair
  }
  std::sort(h.begin(), h.end());
  h.erase(std::unique(h.begin(), h.end(), [](const ContactMemory& p, const ContactMemory& q) { return p.pair == q.pair && p.feature == q.feature; }),
          h.end());
  return h;
}

TEST(ContactHistoryIndex, FindsWhatTheBinarySearchFinds) {
  std::mt19937 rng(2006);
  for (const std::size_t n : {0u, 1u, 7u, 1800u, 20000u}) {
    const ContactHistory h = random_history(n, 1000, rng);
    ContactHistoryIndex index;
    index.build(h);
    for (const ContactMemory& m : h) EXPECT_EQ(index.find(h, m.pair, m.feature), &m);
    // probes of every kind: pairs and features in and out of the history
    std::size_t found = 0;
    for (int k = 0; k < 20000; ++k) {
      const ContactMemory& near = h.empty() ? ContactMemory{} : h[rng() % h.size()];
      const std::uint64_t pair = rng() % 2 ? near.pair : near.pair + (rng() % 3);
      const std::uint32_t feature = rng() % 2 ? near.feature : near.feature ^ (1u << (rng() % 32));
      const ContactMemory* expect = binary_search(h, pair, feature);
      ASSERT_EQ(index.find(h, pair, feature), expect) << "n " << n << " pair " << pair << " feature " << feature;
      found += expect != nullptr;
    }
    if (n > 0) {
      EXPECT_GT(found, 5000u);  // the probes met the history as well as missed it
    }
  }
}

TEST(ContactHistoryIndex, EqualKeysGiveTheFirstAndAnEmptyIndexNothing) {
  ContactHistory h{{5, 1, 1.0, 0.0}, {5, 2, 2.0, 0.0}, {5, 2, 3.0, 0.0}, {7, 2, 4.0, 0.0}};
  ContactHistoryIndex index;
  EXPECT_EQ(index.find(h, 5, 1), nullptr);  // never built
  index.build(h);
  ASSERT_NE(index.find(h, 5, 2), nullptr);
  EXPECT_EQ(index.find(h, 5, 2), binary_search(h, 5, 2));
  EXPECT_EQ(index.find(h, 5, 2)->rn, 2.0);
  EXPECT_EQ(index.find(h, 7, 1), nullptr);
  // rebuilt over another history: the old keys are gone
  const ContactHistory other{{9, 9, 1.0, 0.0}};
  index.build(other);
  EXPECT_EQ(index.find(other, 5, 1), nullptr);
  EXPECT_EQ(index.find(other, 9, 9), &other[0]);
  index.build(ContactHistory{});
  EXPECT_EQ(index.find(other, 9, 9), nullptr);
}

TEST(ContactHistoryIndex, ARangeOfLookupsFindsWhatFindFinds) {
  // find_range, with its prefetching pipeline (a history above kCachedBytes) and without it:
  // the same answers as find for every key, in order, on whole ranges and on pieces of them
  // (a thread's share), shorter than the pipeline too
  std::mt19937 rng(27);
  const std::size_t large = 2 * ContactHistoryIndex::kCachedBytes / sizeof(ContactMemory);
  for (const std::size_t n : {0u, 5u, 3000u, static_cast<unsigned>(large)}) {
    const ContactHistory h = random_history(n, n > 10000 ? 40000 : 1000, rng);
    ContactHistoryIndex index;
    index.build(h);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keys;
    for (int k = 0; k < 50000; ++k) {
      const ContactMemory& near = h.empty() ? ContactMemory{} : h[rng() % h.size()];
      keys.push_back({rng() % 2 ? near.pair : near.pair + 1, rng() % 4 ? near.feature : near.feature ^ 4u});
    }
    auto key = [&](std::size_t i) { return keys[i]; };
    std::vector<std::uint32_t> got(keys.size(), 7u);
    std::vector<std::size_t> order;
    auto found = [&](std::size_t i, std::uint32_t k) {
      got[i] = k;
      order.push_back(i);
    };
    const std::size_t cuts[] = {0, 3, 20, 21, 9000, 33333, keys.size()};
    for (std::size_t c = 0; c + 1 < std::size(cuts); ++c) index.find_range(h, cuts[c], cuts[c + 1], key, found);
    ASSERT_EQ(order.size(), keys.size());
    std::size_t hits = 0;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      ASSERT_EQ(order[i], i);  // one key after the other
      const ContactMemory* expect = index.find(h, keys[i].first, keys[i].second);
      ASSERT_EQ(got[i], expect ? static_cast<std::uint32_t>(expect - h.data()) : ContactHistoryIndex::kNone) << "n " << n << " key " << i;
      hits += expect != nullptr;
    }
    if (n > 0) {
      EXPECT_GT(hits, keys.size() / 4);
    }
    if (n == large) {
      EXPECT_GT(h.size() * sizeof(ContactMemory), ContactHistoryIndex::kCachedBytes);  // the pipeline ran
    }
  }
}

TEST(ContactHistoryIndex, BuiltOnThreadsFindsTheFirstOfEqualKeys) {
  // keys in any order, many of them twice or more (entries k and later of the same key): built
  // on 2, 3 and 4 threads, every key finds what the one-thread build finds, the smallest entry
  std::mt19937 rng(37);
  ContactHistory h = random_history(30000, 3000, rng);
  const std::size_t distinct = h.size();
  for (std::size_t i = 0; i < distinct; i += 3) h.push_back({h[i].pair, h[i].feature, -1.0, 0.0});
  for (std::size_t i = 0; i < distinct; i += 7) h.push_back({h[i].pair, h[i].feature, -2.0, 0.0});
  std::shuffle(h.begin(), h.end(), rng);
  ContactHistoryIndex one;
  one.build(h);
  std::size_t firsts_not_at_home = 0;
  for (const int threads : {2, 3, 4}) {
    for (int round = 0; round < 3; ++round) {
      ContactHistoryIndex many;
      many.build(h, threads);
      for (std::size_t k = 0; k < h.size(); ++k) {
        const ContactMemory* expect = one.find(h, h[k].pair, h[k].feature);
        ASSERT_LE(expect, &h[k]);  // the first of its key
        ASSERT_EQ(many.find(h, h[k].pair, h[k].feature), expect) << threads << " threads, entry " << k;
        firsts_not_at_home += expect != &h[k];
      }
      ASSERT_EQ(many.find(h, 3, 3), nullptr);
    }
  }
  EXPECT_GT(firsts_not_at_home, 1000u);  // the duplicates were met
}

}  // namespace
}  // namespace nscd
