#include "core/block_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace moorsim {

namespace {

// Position of (row, col) in the pattern's values, or -1.
int64_t Find(const SparsityPattern& p, int row, int col) {
  const auto begin = p.column.begin() + p.row_start[row];
  const auto end = p.column.begin() + p.row_start[row + 1];
  const auto it = std::lower_bound(begin, end, static_cast<int64_t>(col));
  return (it != end && *it == col) ? it - p.column.begin() : -1;
}

// Entries of M = I - gamma J: off the diagonal, and on it.
double OffDiagonal(const double* jacobian, int64_t slot, double gamma) {
  return slot < 0 ? 0.0 : -gamma * jacobian[slot];
}
double OnDiagonal(const double* jacobian, int64_t slot, double gamma) {
  return 1.0 + OffDiagonal(jacobian, slot, gamma);
}

// Inverse of a 3x3 pivot block; false if it is singular or not finite.
bool Invert(const Mat3& a, Mat3* inverse) {
  bool invertible = false;
  double determinant = 0.0;
  a.computeInverseAndDetWithCheck(*inverse, determinant, invertible,
                                  1e-300 * std::max(1.0, a.cwiseAbs().maxCoeff()));
  return invertible && std::isfinite(determinant) && inverse->allFinite();
}

}  // namespace

BorderedBlockSolver::BorderedBlockSolver(const SparsityPattern& pattern,
                                         const BlockStructure& structure)
    : size_(pattern.size), border_(structure.border) {
  const int n = size_;
  const int nb = border_;
  // Which part owns each state: -1 border, else the node's index in nodes_.
  std::vector<int> owner(n, -2);
  auto fail = [](const std::string& what) {
    throw ContractError("block structure does not fit the Jacobian: " + what);
  };
  if (nb < 0 || nb > n) fail("border size " + std::to_string(nb));
  for (int i = 0; i < nb; ++i) owner[i] = -1;
  for (const NodeChain& chain : structure.chains) {
    ChainSlots cs;
    cs.first_node = static_cast<int>(nodes_.size());
    cs.nodes = chain.nodes;
    if (chain.nodes <= 0 || chain.first_state < nb || chain.first_state + 6 * chain.nodes > n) {
      fail("a chain of " + std::to_string(chain.nodes) + " nodes at state " +
           std::to_string(chain.first_state));
    }
    for (int k = 0; k < chain.nodes; ++k) {
      NodeSlots node;
      node.state = chain.first_state + 6 * k;
      for (int s = 0; s < 6; ++s) {
        if (owner[node.state + s] != -2) fail("state " + std::to_string(node.state + s) + " twice");
        owner[node.state + s] = static_cast<int>(nodes_.size());
      }
      nodes_.push_back(node);
    }
    chains_.push_back(cs);
  }
  for (int i = 0; i < n; ++i) {
    if (owner[i] == -2) fail("state " + std::to_string(i) + " in no block");
  }

  // Every allowed entry gets its slot; every pattern entry must be allowed.
  std::vector<char> used(pattern.nnz(), 0);
  auto slot = [&](int row, int col) {
    const int64_t s = Find(pattern, row, col);
    if (s >= 0) used[s] = 1;
    return s;
  };
  border_slots_.resize(static_cast<std::size_t>(nb) * nb);
  for (int r = 0; r < nb; ++r) {
    for (int c = 0; c < nb; ++c) border_slots_[r * nb + c] = slot(r, c);
  }
  for (ChainSlots& cs : chains_) {
    for (int k = 0; k < cs.nodes; ++k) {
      NodeSlots& node = nodes_[cs.first_node + k];
      for (int a = 0; a < 3; ++a) {
        node.p[a] = slot(node.state + a, node.state + a);
        node.q[a] = slot(node.state + a, node.state + 3 + a);
        if (node.p[a] < 0) fail("no diagonal entry in row " + std::to_string(node.state + a));
        for (int j = 0; j < 3; ++j) {
          const int neighbour = k + j - 1;
          for (int c = 0; c < 6; ++c) {
            const bool exists = neighbour >= 0 && neighbour < cs.nodes;
            const int col = exists ? nodes_[cs.first_node + neighbour].state + c : -1;
            node.v[(a * 3 + j) * 6 + c] = exists ? slot(node.state + 3 + a, col) : kAbsent;
          }
        }
      }
    }
    const NodeSlots& last = nodes_[cs.first_node + cs.nodes - 1];
    cs.node_border.resize(3 * nb);
    cs.border_node.resize(nb * 6);
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < nb; ++b) {
        cs.node_border[a * nb + b] = slot(last.state + 3 + a, b);
        cs.coupled = cs.coupled || cs.node_border[a * nb + b] >= 0;
      }
    }
    for (int b = 0; b < nb; ++b) {
      for (int c = 0; c < 6; ++c) {
        cs.border_node[b * 6 + c] = slot(b, last.state + c);
        cs.coupled = cs.coupled || cs.border_node[b * 6 + c] >= 0;
      }
    }
    if (cs.nodes < 2) continue;
    // The head: the border states the first node's rows or columns meet.
    const NodeSlots& first = nodes_[cs.first_node];
    for (int b = 0; b < nb; ++b) {
      bool meets = false;
      for (int a = 0; a < 3; ++a) meets = meets || Find(pattern, first.state + 3 + a, b) >= 0;
      for (int c = 0; c < 6; ++c) meets = meets || Find(pattern, b, first.state + c) >= 0;
      if (meets) cs.head.push_back(b);
    }
    const int nh = static_cast<int>(cs.head.size());
    cs.head_node_border.resize(3 * nh);
    cs.head_border_node.resize(nh * 6);
    for (int h = 0; h < nh; ++h) {
      for (int a = 0; a < 3; ++a)
        cs.head_node_border[a * nh + h] = slot(first.state + 3 + a, cs.head[h]);
      for (int c = 0; c < 6; ++c)
        cs.head_border_node[h * 6 + c] = slot(cs.head[h], first.state + c);
    }
    cs.coupled = cs.coupled || nh > 0;
  }
  for (int r = 0; r < n; ++r) {
    for (int64_t s = pattern.row_start[r]; s < pattern.row_start[r + 1]; ++s) {
      if (!used[s]) {
        std::ostringstream msg;
        msg << "entry (" << r << ", " << pattern.column[s] << ") is outside the blocks";
        fail(msg.str());
      }
    }
  }

  node_factors_.resize(nodes_.size());
  chain_factors_.resize(chains_.size());
  for (std::size_t c = 0; c < chains_.size(); ++c) {
    ChainFactor& f = chain_factors_[c];
    f.C = Mat3X::Zero(3, nb);
    f.B = MatX3::Zero(nb, 3);
    f.Wb = MatX3::Zero(nb, 3);
    const int nh = static_cast<int>(chains_[c].head.size());
    if (nh == 0) continue;
    f.F.assign(chains_[c].nodes - 1, Mat3X::Zero(3, nh));
    f.RG.assign(chains_[c].nodes - 1, MatX3::Zero(nh, 3));
    f.Wh = MatX3::Zero(nh, 3);
  }
  y_.resize(nodes_.size());
  border_matrix_ = MatX::Zero(nb, nb);
  gc_ = Mat3X::Zero(3, nb);
  border_rhs_ = VecX::Zero(nb);
  border_x_ = VecX::Zero(nb);
}

void BorderedBlockSolver::FactorHead(const double* jacobian, double gamma, const ChainSlots& cs,
                                     ChainFactor* cf) {
  const int nh = static_cast<int>(cs.head.size());
  const int n = cs.nodes;
  const NodeFactor& ff = node_factors_[cs.first_node];
  // The first node: its rows in the head columns, the head rows in its reduced unknowns.
  Mat3X& f0 = cf->F[0];
  for (int a = 0; a < 3; ++a) {
    for (int h = 0; h < nh; ++h)
      f0(a, h) = OffDiagonal(jacobian, cs.head_node_border[a * nh + h], gamma);
  }
  MatX3& r = head_fill_;
  r.resize(nh, 3);
  for (int h = 0; h < nh; ++h) {
    for (int c = 0; c < 3; ++c) {
      const double m_br = OffDiagonal(jacobian, cs.head_border_node[h * 6 + c], gamma);
      const double m_bv = OffDiagonal(jacobian, cs.head_border_node[h * 6 + 3 + c], gamma);
      cf->Wh(h, c) = m_br * ff.p_inverse[c];
      r(h, c) = m_bv - m_br * ff.q_over_p[c];
    }
  }
  // Down the chain: F_k = -E_k F_{k-1}, R_k = -R_{k-1} G_{k-1} U_{k-1}, and each eliminated
  // node's R_k G_k F_k off the border's head block.
  for (int k = 0; k < n - 1; ++k) {
    const NodeFactor& f = node_factors_[cs.first_node + k];
    if (k > 0) {
      cf->F[k].noalias() = -f.E * cf->F[k - 1];
      r.noalias() = -cf->RG[k - 1] * node_factors_[cs.first_node + k - 1].U;
    }
    cf->RG[k].noalias() = r * f.G;
    for (int i = 0; i < nh; ++i) {
      for (int j = 0; j < nh; ++j) {
        border_matrix_(cs.head[i], cs.head[j]) -= cf->RG[k].row(i).dot(cf->F[k].col(j));
      }
    }
  }
  // The last node's fill joins its own border coupling.
  const NodeFactor& lf = node_factors_[cs.first_node + n - 1];
  head_column_.noalias() = -lf.E * cf->F[n - 2];
  r.noalias() = -cf->RG[n - 2] * node_factors_[cs.first_node + n - 2].U;
  for (int h = 0; h < nh; ++h) {
    cf->C.col(cs.head[h]) += head_column_.col(h);
    cf->B.row(cs.head[h]) += r.row(h);
  }
}

bool BorderedBlockSolver::Factor(const double* jacobian, double gamma) {
  const int nb = border_;
  MatX& border = border_matrix_;
  for (int r = 0; r < nb; ++r) {
    for (int c = 0; c < nb; ++c) {
      const int64_t slot = border_slots_[r * nb + c];
      border(r, c) =
          r == c ? OnDiagonal(jacobian, slot, gamma) : OffDiagonal(jacobian, slot, gamma);
    }
  }
  for (std::size_t ci = 0; ci < chains_.size(); ++ci) {
    const ChainSlots& cs = chains_[ci];
    // The kinematic rows first: p and q of every node (needed by the neighbours' blocks).
    for (int k = 0; k < cs.nodes; ++k) {
      const NodeSlots& node = nodes_[cs.first_node + k];
      NodeFactor& f = node_factors_[cs.first_node + k];
      Vec3 p, q;
      for (int a = 0; a < 3; ++a) {
        p[a] = OnDiagonal(jacobian, node.p[a], gamma);
        q[a] = OffDiagonal(jacobian, node.q[a], gamma);
      }
      if (!(p.cwiseAbs().minCoeff() > 0.0) || !q.allFinite()) return false;
      f.p_inverse = p.cwiseInverse();
      f.q_over_p = q.cwiseProduct(f.p_inverse);
    }
    for (int k = 0; k < cs.nodes; ++k) {
      const NodeSlots& node = nodes_[cs.first_node + k];
      NodeFactor& f = node_factors_[cs.first_node + k];
      // Reduced blocks A_j = M_vv(j) - M_vr(j) diag(q_j / p_j), W_j = M_vr(j) diag(1 / p_j).
      std::array<Mat3, 3> reduced;
      for (int j = 0; j < 3; ++j) {
        const int neighbour = k + j - 1;
        if (neighbour < 0 || neighbour >= cs.nodes) {
          reduced[j].setZero();
          f.W[j].setZero();
          continue;
        }
        const NodeFactor& nf = node_factors_[cs.first_node + neighbour];
        for (int a = 0; a < 3; ++a) {
          for (int c = 0; c < 3; ++c) {
            const double m_vr = OffDiagonal(jacobian, node.v[(a * 3 + j) * 6 + c], gamma);
            double m_vv = OffDiagonal(jacobian, node.v[(a * 3 + j) * 6 + 3 + c], gamma);
            if (j == 1 && c == a) m_vv += 1.0;  // the diagonal of M
            f.W[j](a, c) = m_vr * nf.p_inverse[c];
            reduced[j](a, c) = m_vv - m_vr * nf.q_over_p[c];
          }
        }
      }
      Mat3 pivot = reduced[1];
      if (k > 0) {
        const NodeFactor& prev = node_factors_[cs.first_node + k - 1];
        f.E = reduced[0] * prev.G;  // L_k G_{k-1}
        pivot -= f.E * prev.U;
      }
      if (!Invert(pivot, &f.G)) return false;
      f.U = reduced[2];
    }
    ChainFactor& cf = chain_factors_[ci];
    if (!cs.coupled) continue;
    const NodeFactor& lf = node_factors_[cs.first_node + cs.nodes - 1];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < nb; ++b) {
        cf.C(a, b) = OffDiagonal(jacobian, cs.node_border[a * nb + b], gamma);
      }
    }
    for (int b = 0; b < nb; ++b) {
      for (int c = 0; c < 3; ++c) {
        const double m_br = OffDiagonal(jacobian, cs.border_node[b * 6 + c], gamma);
        const double m_bv = OffDiagonal(jacobian, cs.border_node[b * 6 + 3 + c], gamma);
        cf.Wb(b, c) = m_br * lf.p_inverse[c];
        cf.B(b, c) = m_bv - m_br * lf.q_over_p[c];
      }
    }
    if (!cs.head.empty()) FactorHead(jacobian, gamma, cs, &cf);
    gc_.noalias() = lf.G * cf.C;
    border.noalias() -= cf.B * gc_;
  }
  if (nb > 0) {
    if (!border.allFinite()) return false;
    border_lu_.compute(border);
    if (!(border_lu_.matrixLU().diagonal().cwiseAbs().minCoeff() > 0.0)) return false;
  }
  return true;
}

void BorderedBlockSolver::Solve(const double* b, double* x) {
  const int nb = border_;
  for (int i = 0; i < nb; ++i) border_rhs_[i] = b[i];
  // Forward: y_k = b_v,k - sum_j W_j b_r,j - E_k y_{k-1}.
  for (std::size_t ci = 0; ci < chains_.size(); ++ci) {
    const ChainSlots& cs = chains_[ci];
    for (int k = 0; k < cs.nodes; ++k) {
      const int g = cs.first_node + k;
      const NodeFactor& f = node_factors_[g];
      const double* bk = b + nodes_[g].state;
      Vec3 y(bk[3], bk[4], bk[5]);
      for (int j = 0; j < 3; ++j) {
        const int neighbour = k + j - 1;
        if (neighbour < 0 || neighbour >= cs.nodes) continue;
        y.noalias() -= f.W[j] * Eigen::Map<const Vec3>(b + nodes_[g + j - 1].state);
      }
      if (k > 0) y.noalias() -= f.E * y_[g - 1];
      y_[g] = y;
    }
    const ChainFactor& cf = chain_factors_[ci];
    if (!cs.head.empty()) {
      // The head rows: -Wh b_r of the first node - sum_k R_k G_k y_k.
      head_x_.noalias() = cf.Wh * Eigen::Map<const Vec3>(b + nodes_[cs.first_node].state);
      for (int k = 0; k < cs.nodes - 1; ++k) head_x_.noalias() += cf.RG[k] * y_[cs.first_node + k];
      for (std::size_t h = 0; h < cs.head.size(); ++h) border_rhs_[cs.head[h]] -= head_x_[h];
    }
    if (cs.coupled) {
      const int g = cs.first_node + cs.nodes - 1;
      border_rhs_.noalias() -= cf.Wb * Eigen::Map<const Vec3>(b + nodes_[g].state);
      border_rhs_.noalias() -= cf.B * (node_factors_[g].G * y_[g]);
    }
  }
  if (nb > 0) border_x_ = border_lu_.solve(border_rhs_);
  // Backward: dv_k = G_k (y_k - U_k dv_{k+1}) (the last node: y - C x_border), then
  // dr_k = (b_r,k - q_k dv_k) / p_k. y_ is overwritten by dv; b is read before x is written
  // at each node (b_r of a node is only needed by itself here).
  for (std::size_t ci = 0; ci < chains_.size(); ++ci) {
    const ChainSlots& cs = chains_[ci];
    const ChainFactor& cf = chain_factors_[ci];
    const int nh = static_cast<int>(cs.head.size());
    if (nh > 0) {
      head_x_.resize(nh);
      for (int h = 0; h < nh; ++h) head_x_[h] = border_x_[cs.head[h]];
    }
    for (int k = cs.nodes - 1; k >= 0; --k) {
      const int g = cs.first_node + k;
      const NodeFactor& f = node_factors_[g];
      Vec3 rhs = y_[g];
      if (k == cs.nodes - 1) {
        if (cs.coupled) rhs.noalias() -= cf.C * border_x_;
      } else {
        rhs.noalias() -= f.U * y_[g + 1];
        if (nh > 0) rhs.noalias() -= cf.F[k] * head_x_;
      }
      const Vec3 dv = f.G * rhs;
      y_[g] = dv;
      double* xk = x + nodes_[g].state;
      const double* bk = b + nodes_[g].state;
      for (int a = 0; a < 3; ++a) {
        const double br = bk[a];
        xk[3 + a] = dv[a];
        xk[a] = br * f.p_inverse[a] - f.q_over_p[a] * dv[a];
      }
    }
  }
  for (int i = 0; i < nb; ++i) x[i] = border_x_[i];
}

}  // namespace moorsim
