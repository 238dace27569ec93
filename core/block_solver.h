// A direct solver for the Newton matrices M = I - gamma J of a rigid body carrying chains of
// lumped masses (the vessel and its mooring lines), exploiting their structure instead of a
// general sparse LU:
//
//   * each chain node has states [r (3), v (3)] and its position rows are r' = v, so the
//     rows of r in M hold only a diagonal p and the entry q in the column of v. Substituting
//     dr = (b_r - q dv) / p leaves one 3x3 block per node pair in the unknowns dv (the Schur
//     complement of the kinematic rows, half the size);
//   * each node's velocity rows couple to its two neighbours only: the reduced chain is block
//     tridiagonal and is factored by block Gaussian elimination from the chain's first node
//     to its last (the block Thomas algorithm), with no fill-in;
//   * a dense border (the body's states, the free points where lines meet) couples to the
//     last node of each chain (the node next to the fairlead or the point above) and may
//     couple to its first node (the node next to a point below). The last node's pivot is
//     that node's Schur complement and the border's reduced matrix is its own block minus
//     one correction per chain; a chain coupled at its first node carries that coupling down
//     the sweep as a fill of a few columns and rows (the border states the first node sees,
//     six for a point), so its cost grows with those columns only. The border is factored
//     densely with partial pivoting.
//
// No pivoting across nodes: every pivot block is checked (a singular or non-finite one makes
// Factor() return false, which the integrator reports to CVODE as a recoverable failure, so
// it retries with a smaller step). The structure is validated against the Jacobian's pattern
// once: an entry the structure does not allow is an error.
#pragma once

#include <Eigen/LU>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/ode_system.h"
#include "core/types.h"

namespace moorsim {

class BorderedBlockSolver {
 public:
  /// Throws ContractError naming the first pattern entry the structure does not allow, or a
  /// state the structure leaves out.
  BorderedBlockSolver(const SparsityPattern& pattern, const BlockStructure& structure);

  /// Factors M = I - gamma J, J given by its values in the pattern's order (M is formed
  /// entry by entry as the blocks are read; no copy of the matrix is made). False if a pivot
  /// block (a node's 3x3 or the border's) is singular or not finite.
  bool Factor(const double* jacobian, double gamma);
  /// x = M^{-1} b with the last successful factorisation; b and x may be the same array.
  void Solve(const double* b, double* x);

 private:
  using Mat3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;
  using MatX3 = Eigen::Matrix<double, Eigen::Dynamic, 3>;
  static constexpr int64_t kAbsent = -1;

  // Where each entry of a node's rows sits in the values array (kAbsent: structurally zero).
  struct NodeSlots {
    int state = 0;                    // first state (r) of the node
    std::array<int64_t, 3> p{}, q{};  // (r_a, r_a) and (r_a, v_a)
    // (v_a, column c of node k + j - 1) for j = 0, 1, 2 (previous, this, next), c = 0..5.
    std::array<int64_t, 3 * 3 * 6> v{};
  };
  struct ChainSlots {
    int first_node = 0;  // index into nodes_
    int nodes = 0;
    bool coupled = false;              // the last node couples to the border
    std::vector<int64_t> node_border;  // (v_a of the last node, border column b): 3 x nb
    std::vector<int64_t> border_node;  // (border row b, column c of the last node): nb x 6
    // The border states the first node couples to (chains of two nodes or more; empty: none)
    // and their slots: (v_a of the first node, head[h]) 3 x nh, (head[h], column c) nh x 6.
    std::vector<int> head;
    std::vector<int64_t> head_node_border;
    std::vector<int64_t> head_border_node;
  };
  // The factorisation, per node: the pivot's inverse G, the multiplier E = L G_prev, the
  // upper block U (coupling to the next node), the right-hand side transforms W_j = M_vr(j)
  // diag(1 / p_j) of the three neighbours, and 1 / p and q / p of the kinematic rows.
  struct NodeFactor {
    Mat3 G, E, U;
    std::array<Mat3, 3> W;
    Vec3 p_inverse, q_over_p;
  };
  struct ChainFactor {
    Mat3X C;   // the last node's velocity rows in the border columns (3 x nb)
    MatX3 B;   // the border rows in the last node's reduced unknowns dv (nb x 3)
    MatX3 Wb;  // the border rows' transform of the last node's b_r (nb x 3)
    // With a head coupling, per node but the last: the fill F_k of its rows in the head
    // columns (3 x nh) and R_k G_k, the head rows' fill times the pivot's inverse (nh x 3);
    // and the head rows' transform of the first node's b_r (nh x 3).
    std::vector<Mat3X> F;
    std::vector<MatX3> RG;
    MatX3 Wh;
  };

  // The fill a chain's head coupling leaves down the chain and on the border.
  void FactorHead(const double* jacobian, double gamma, const ChainSlots& cs, ChainFactor* cf);

  int size_ = 0;
  int border_ = 0;
  std::vector<int64_t> border_slots_;  // (border row, border column): nb x nb
  std::vector<NodeSlots> nodes_;
  std::vector<ChainSlots> chains_;
  std::vector<NodeFactor> node_factors_;
  std::vector<ChainFactor> chain_factors_;
  MatX border_matrix_;  // the border's reduced matrix, factored into border_lu_
  Mat3X gc_;            // scratch: G C of one chain
  MatX3 head_fill_;     // scratch: the head rows' fill R_k of the node being eliminated
  Mat3X head_column_;   // scratch: the last node's fill in the head columns
  VecX head_x_;         // scratch: the border's solution in one chain's head columns
  Eigen::PartialPivLU<MatX> border_lu_;
  // Scratch for Solve(): the reduced right-hand sides y, then the velocity unknowns.
  std::vector<Vec3> y_;
  VecX border_rhs_;  // the border's reduced right-hand side
  VecX border_x_;    // and its solution
};

}  // namespace moorsim
