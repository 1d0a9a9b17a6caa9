#pragma once
/// @file consistency_graph.hpp
/// Which loop closures agree with each other: a graph whose vertices are loop closures and whose
/// edges join two that are pairwise consistent (the cycle they close with the dead reckoning
/// between their ends is the identity within its covariance), and its largest clique, the largest
/// set of loop closures that all agree: the pairwise consistent measurement set maximisation of
/// Mangelson, Dominic, Eustice & Vasudevan 2018 ("Pairwise consistent measurement set maximization
/// for robust multi-robot map merging", ICRA). Wrong loop closures rarely agree with each other or
/// with the right ones, so the largest clique keeps the right ones however many wrong ones there are.
///
/// The clique is found greedily (a heuristic as PCM's own, after Pattabiraman et al. 2015, "Fast
/// algorithms for the maximum clique problem on massive graphs"): from a seed, repeatedly add the
/// candidate with the most neighbours among the remaining candidates. Deterministic: ties go to the
/// lower index.

#include <cstddef>
#include <vector>

namespace sonarmap {

class ConsistencyGraph {
 public:
  /// Adds a vertex joined to `neighbours` (earlier vertices); returns its index.
  /// @throws ValueError for a neighbour that is not an earlier vertex.
  std::size_t addVertex(const std::vector<std::size_t>& neighbours);
  std::size_t size() const { return neighbours_.size(); }
  bool joined(std::size_t a, std::size_t b) const;
  const std::vector<std::size_t>& neighbours(std::size_t vertex) const { return neighbours_.at(vertex); }

  /// The largest clique found greedily from `seed` (it included), in increasing order.
  std::vector<std::size_t> cliqueFrom(std::size_t seed) const;
  /// The largest of cliqueFrom over the `seeds` most connected vertices (all when 0), the first
  /// found on a tie (seeds taken by decreasing degree, then index; a seed inside the largest so far,
  /// or with too few neighbours to beat it, is skipped). Empty for an empty graph. Cost: a clique
  /// from a seed of degree d costs O(d² · n / 64) on bit sets.
  std::vector<std::size_t> largestClique(std::size_t seeds = 0) const;

 private:
  std::vector<std::vector<std::size_t>> neighbours_;  ///< sorted
};

}  // namespace sonarmap
