// The bordered block-tridiagonal solver against a dense LU of the same matrix, on random
// matrices of the structure it is built for, and its refusals.
#include "core/block_solver.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "core/error.h"

namespace moorsim {
namespace {

// A Newton matrix M = I - gamma J with the structure of a body carrying chains: border rows dense
// among themselves and coupled to the last node of the coupled chains; position rows p r + q v;
// velocity rows coupled to the neighbouring nodes (all 6 columns) and, at a coupled chain's
// last node, to the border. Random values, diagonally dominant velocity blocks.
struct Bordered {
  SparsityPattern pattern;
  BlockStructure structure;
  std::vector<double> values;  // M in the pattern's order
  MatX dense;                  // M
  double gamma = 0.4;
  // J = (I - M) / gamma in the pattern's order, what the solver takes.
  std::vector<double> Jacobian(const std::vector<double>& m) const {
    std::vector<double> j(m.size());
    for (int r = 0; r < pattern.size; ++r) {
      for (int64_t s = pattern.row_start[r]; s < pattern.row_start[r + 1]; ++s) {
        j[s] = ((pattern.column[s] == r ? 1.0 : 0.0) - m[s]) / gamma;
      }
    }
    return j;
  }
};

// `head[ci]` couples chain ci's first node too, to the border states 2, 3, ..., 7 (a free
// point's six states, as a line hanging from a point sees them).
Bordered MakeBordered(int border, const std::vector<int>& chain_nodes,
                      const std::vector<bool>& coupled, unsigned seed,
                      const std::vector<bool>& head = {}) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Bordered m;
  m.structure.border = border;
  int n = border;
  for (int nodes : chain_nodes) {
    m.structure.chains.push_back({n, nodes});
    n += 6 * nodes;
  }
  m.dense = MatX::Zero(n, n);
  std::vector<std::vector<int>> columns(n);
  auto set = [&](int r, int c, double v) {
    m.dense(r, c) = v;
    columns[r].push_back(c);
  };
  for (int r = 0; r < border; ++r) {
    for (int c = 0; c < border; ++c) set(r, c, (r == c ? 4.0 * border : 0.0) + u(rng));
  }
  for (std::size_t ci = 0; ci < chain_nodes.size(); ++ci) {
    const NodeChain& chain = m.structure.chains[ci];
    for (int k = 0; k < chain.nodes; ++k) {
      const int s = chain.first_state + 6 * k;
      for (int a = 0; a < 3; ++a) {
        set(s + a, s + a, 1.0 + 0.5 * u(rng));  // p: not always 1
        set(s + 3 + a, s + 3 + a, 0.0);
        set(s + a, s + 3 + a, -0.3 + 0.1 * u(rng));  // q = -gamma
      }
      for (int a = 0; a < 3; ++a) {
        const int row = s + 3 + a;
        for (int j = std::max(0, k - 1); j <= std::min(chain.nodes - 1, k + 1); ++j) {
          for (int c = 0; c < 6; ++c) {
            const int col = chain.first_state + 6 * j + c;
            set(row, col, (col == row ? 30.0 : 0.0) + u(rng));
          }
        }
      }
      if (k == 0 && ci < head.size() && head[ci]) {
        for (int b = 2; b < std::min(border, 8); ++b) {
          for (int a = 0; a < 3; ++a) set(s + 3 + a, b, u(rng));
          for (int c = 0; c < 6; ++c) set(b, s + c, u(rng));
        }
      }
      const bool last = k == chain.nodes - 1;
      if (last && coupled[ci]) {
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < border; ++b) set(s + 3 + a, b, u(rng));
        }
        for (int b = 0; b < border; ++b) {
          for (int c = 0; c < 6; ++c) set(b, s + c, u(rng));
        }
      }
    }
  }
  m.pattern.size = n;
  m.pattern.row_start.push_back(0);
  for (int r = 0; r < n; ++r) {
    std::sort(columns[r].begin(), columns[r].end());
    columns[r].erase(std::unique(columns[r].begin(), columns[r].end()), columns[r].end());
    for (int c : columns[r]) {
      m.pattern.column.push_back(c);
      m.values.push_back(m.dense(r, c));
    }
    m.pattern.row_start.push_back(static_cast<int64_t>(m.pattern.column.size()));
  }
  return m;
}

double RelativeError(const VecX& x, const VecX& reference) {
  return (x - reference).norm() / reference.norm();
}

// A normally distributed right-hand side of the matrix's size, from `seed`.
VecX RandomRightHandSide(const Bordered& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  VecX b(m.pattern.size);
  for (int i = 0; i < b.size(); ++i) b[i] = g(rng);
  return b;
}

TEST(BorderedBlockSolver, MatchesDenseLuOnBorderedChains) {
  // Chains of 1, 2, 5 and 40 nodes, one of them not coupled to the border; several seeds.
  for (unsigned seed = 1; seed <= 5; ++seed) {
    Bordered m = MakeBordered(14, {1, 2, 5, 40, 7}, {true, true, true, true, false}, seed);
    BorderedBlockSolver solver(m.pattern, m.structure);
    ASSERT_TRUE(solver.Factor(m.Jacobian(m.values).data(), m.gamma));
    const VecX b = RandomRightHandSide(m, seed + 100);
    const VecX reference = m.dense.fullPivLu().solve(b);
    VecX x(b.size());
    solver.Solve(b.data(), x.data());
    EXPECT_LT(RelativeError(x, reference), 1e-12) << "seed " << seed;
    // In place (CVODE may pass the same vector) and a second right-hand side.
    VecX y = b;
    solver.Solve(y.data(), y.data());
    EXPECT_LT(RelativeError(y, reference), 1e-12);
    const VecX b2 = VecX::Ones(b.size());
    solver.Solve(b2.data(), x.data());
    EXPECT_LT(RelativeError(x, m.dense.fullPivLu().solve(b2)), 1e-12);
  }
}

TEST(BorderedBlockSolver, MatchesDenseLuWithChainsCoupledAtBothEnds) {
  // Lines between free points and the body: chains coupled to the border at their first
  // node, at both ends, or at the first only; of 2, 3 and 30 nodes.
  for (unsigned seed = 1; seed <= 5; ++seed) {
    Bordered m = MakeBordered(20, {2, 30, 3, 30, 1, 5}, {true, true, false, false, true, true},
                              seed, {true, true, true, true, false, false});
    BorderedBlockSolver solver(m.pattern, m.structure);
    ASSERT_TRUE(solver.Factor(m.Jacobian(m.values).data(), m.gamma));
    const VecX b = RandomRightHandSide(m, seed + 200);
    const VecX reference = m.dense.fullPivLu().solve(b);
    VecX x = b;
    solver.Solve(x.data(), x.data());
    EXPECT_LT(RelativeError(x, reference), 1e-12) << "seed " << seed;
    // Refactored with new values.
    for (double& v : m.values) v *= 0.75;
    ASSERT_TRUE(solver.Factor(m.Jacobian(m.values).data(), m.gamma));
    solver.Solve(b.data(), x.data());
    EXPECT_LT(RelativeError(x, (0.75 * m.dense).fullPivLu().solve(b)), 1e-12);
  }
}

TEST(BorderedBlockSolver, WorksWithoutABorderAndRefactors) {
  Bordered m = MakeBordered(0, {49, 49, 3}, {false, false, false}, 7);
  BorderedBlockSolver solver(m.pattern, m.structure);
  const VecX b = VecX::LinSpaced(m.pattern.size, -1.0, 2.0);
  VecX x(b.size());
  ASSERT_TRUE(solver.Factor(m.Jacobian(m.values).data(), m.gamma));
  solver.Solve(b.data(), x.data());
  EXPECT_LT(RelativeError(x, m.dense.fullPivLu().solve(b)), 1e-12);
  // New values, same pattern: the factorisation is the new matrix's.
  for (double& v : m.values) v *= 1.5;
  ASSERT_TRUE(solver.Factor(m.Jacobian(m.values).data(), m.gamma));
  solver.Solve(b.data(), x.data());
  EXPECT_LT(RelativeError(x, (1.5 * m.dense).fullPivLu().solve(b)), 1e-12);
}

TEST(BorderedBlockSolver, SingularOrNonFinitePivotsAreReported) {
  Bordered m = MakeBordered(3, {4}, {true}, 3);
  BorderedBlockSolver solver(m.pattern, m.structure);
  std::vector<double> values = m.values;
  values[m.pattern.row_start[3]] = 0.0;  // p of the first node's first position row
  EXPECT_FALSE(solver.Factor(m.Jacobian(values).data(), m.gamma));
  values = m.values;
  for (double& v : values) v = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(solver.Factor(m.Jacobian(values).data(), m.gamma));
  // A velocity block that is exactly singular: the first node's velocity rows zeroed.
  values = m.values;
  for (int r = 3 + 3; r < 3 + 6; ++r) {
    for (int64_t s = m.pattern.row_start[r]; s < m.pattern.row_start[r + 1]; ++s) values[s] = 0.0;
  }
  EXPECT_FALSE(solver.Factor(m.Jacobian(values).data(), m.gamma));
  EXPECT_TRUE(solver.Factor(m.Jacobian(m.values).data(), m.gamma));
}

TEST(BorderedBlockSolver, RefusesAPatternOutsideItsStructure) {
  Bordered m = MakeBordered(2, {3, 3}, {true, true}, 5);
  // The chains' order does not matter.
  BlockStructure wrong = m.structure;
  std::swap(wrong.chains[0], wrong.chains[1]);
  EXPECT_NO_THROW(BorderedBlockSolver(m.pattern, wrong));
  wrong = m.structure;
  wrong.chains[0].nodes = 2;  // leaves the third node's states out
  try {
    BorderedBlockSolver solver(m.pattern, wrong);
    FAIL() << "accepted a structure that leaves states out";
  } catch (const ContractError& e) {
    EXPECT_NE(std::string(e.what()).find("in no block"), std::string::npos) << e.what();
  }
  // Two chains read as one: the border couples to the merged chain's third node, which is
  // not its last.
  BlockStructure merged;
  merged.border = 2;
  merged.chains = {{2, 6}};
  EXPECT_THROW(BorderedBlockSolver(m.pattern, merged), ContractError);
  BlockStructure overlapping = m.structure;
  overlapping.chains.push_back(m.structure.chains[0]);
  EXPECT_THROW(BorderedBlockSolver(m.pattern, overlapping), ContractError);
}

}  // namespace
}  // namespace moorsim
