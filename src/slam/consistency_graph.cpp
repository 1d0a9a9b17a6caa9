/// @file consistency_graph.cpp
/// ConsistencyGraph (consistency_graph.hpp): a greedy largest clique on bit sets.

#include "sonarmap/slam/consistency_graph.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// A set of vertices as 64-bit words.
using Bits = std::vector<std::uint64_t>;

Bits bitsOf(const std::vector<std::size_t>& vertices, std::size_t size) {
  Bits bits((size + 63) / 64, 0);
  for (const std::size_t v : vertices) bits[v / 64] |= std::uint64_t{1} << (v % 64);
  return bits;
}

std::size_t commonCount(const Bits& a, const Bits& b) {
  std::size_t count = 0;
  for (std::size_t w = 0; w < a.size(); ++w) count += static_cast<std::size_t>(std::popcount(a[w] & b[w]));
  return count;
}

}  // namespace

std::size_t ConsistencyGraph::addVertex(const std::vector<std::size_t>& neighbours) {
  const std::size_t vertex = neighbours_.size();
  std::vector<std::size_t> sorted = neighbours;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  for (const std::size_t other : sorted) {
    if (other >= vertex) throw ValueError("consistency graph: a vertex may only be joined to earlier vertices");
  }
  for (const std::size_t other : sorted) neighbours_[other].push_back(vertex);  // stays sorted: vertex is the largest
  neighbours_.push_back(std::move(sorted));
  return vertex;
}

bool ConsistencyGraph::joined(std::size_t a, std::size_t b) const {
  const std::vector<std::size_t>& list = neighbours_.at(a);
  return std::binary_search(list.begin(), list.end(), b);
}

std::vector<std::size_t> ConsistencyGraph::cliqueFrom(std::size_t seed) const {
  const std::size_t n = neighbours_.size();
  std::vector<std::size_t> clique{seed};
  Bits candidates = bitsOf(neighbours_.at(seed), n);  // joined to every member so far
  std::vector<Bits> adjacency;  // of the seed's neighbours only: the candidates never leave them
  std::vector<std::size_t> index_of(n, n);
  for (const std::size_t v : neighbours_[seed]) {
    index_of[v] = adjacency.size();
    adjacency.push_back(bitsOf(neighbours_[v], n));
  }
  while (true) {
    // The candidate with the most neighbours among the candidates keeps the most of them; ties go
    // to the lower index.
    std::size_t best = n, best_count = 0;
    for (std::size_t w = 0; w < candidates.size(); ++w) {
      for (std::uint64_t word = candidates[w]; word != 0; word &= word - 1) {
        const std::size_t c = w * 64 + static_cast<std::size_t>(std::countr_zero(word));
        const std::size_t count = commonCount(adjacency[index_of[c]], candidates);
        if (best == n || count > best_count) {
          best = c;
          best_count = count;
        }
      }
    }
    if (best == n) break;
    clique.push_back(best);
    const Bits& joined_to_best = adjacency[index_of[best]];
    for (std::size_t w = 0; w < candidates.size(); ++w) candidates[w] &= joined_to_best[w];
  }
  std::sort(clique.begin(), clique.end());
  return clique;
}

std::vector<std::size_t> ConsistencyGraph::largestClique(std::size_t seeds) const {
  std::vector<std::size_t> order(neighbours_.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [this](std::size_t a, std::size_t b) { return neighbours_[a].size() > neighbours_[b].size(); });
  if (seeds > 0 && seeds < order.size()) order.resize(seeds);
  std::vector<std::size_t> best;
  for (const std::size_t seed : order) {
    // A seed with too few neighbours cannot beat it, and one inside it would find it again.
    if (neighbours_[seed].size() + 1 <= best.size() || std::binary_search(best.begin(), best.end(), seed)) continue;
    std::vector<std::size_t> clique = cliqueFrom(seed);
    if (clique.size() > best.size()) best = std::move(clique);
  }
  return best;
}

}  // namespace sonarmap
