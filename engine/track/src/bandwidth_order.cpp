#include "track/bandwidth_order.hpp"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>
#include <cstdlib>

namespace rumble {

std::vector<Eigen::Index> bandwidth_reducing_order(const Eigen::SparseMatrix<double>& a) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
  Graph graph(static_cast<std::size_t>(a.rows()));
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, j); it; ++it)
      if (it.row() > it.col())
        boost::add_edge(static_cast<Vertex>(it.row()), static_cast<Vertex>(it.col()), graph);
  std::vector<Vertex> reversed(boost::num_vertices(graph));
  boost::cuthill_mckee_ordering(graph, reversed.rbegin());  // written backwards: reverse CM
  return {reversed.begin(), reversed.end()};
}

std::size_t half_bandwidth(const Eigen::SparseMatrix<double>& a,
                           const std::vector<Eigen::Index>& order) {
  std::vector<Eigen::Index> position(static_cast<std::size_t>(a.rows()));
  for (std::size_t k = 0; k < position.size(); ++k)
    position[k] = order.empty() ? static_cast<Eigen::Index>(k) : -1;
  for (std::size_t k = 0; k < order.size(); ++k)
    position[static_cast<std::size_t>(order[k])] = static_cast<Eigen::Index>(k);
  std::size_t band = 0;
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, j); it; ++it)
      band = std::max(
          band, static_cast<std::size_t>(std::abs(position[static_cast<std::size_t>(it.row())] -
                                                  position[static_cast<std::size_t>(it.col())])));
  return band;
}

}  // namespace rumble
