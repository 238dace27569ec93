// The interface between a physical model and the integrator: a first-order ODE
// x' = f(t, x) with a fixed sparse Jacobian pattern per topology.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace moorsim {

/// Compressed sparse row pattern of an n x n Jacobian. Column indices are sorted within a
/// row and every diagonal entry is present (CVODE factors I - gamma J).
struct SparsityPattern {
  int size = 0;
  std::vector<int64_t> row_start;  ///< size + 1 entries
  std::vector<int64_t> column;     ///< nnz entries
  int64_t nnz() const { return row_start.empty() ? 0 : row_start.back(); }
};

/// A chain of lumped masses in the state: `nodes` consecutive nodes of 6 states each,
/// [r (3), v (3)], from `first_state` on, with r' = v and each node's accelerations depending
/// on its neighbours only.
struct NodeChain {
  int first_state = 0;
  int nodes = 0;
};

/// The block structure of a Jacobian that BorderedBlockSolver (core/block_solver.h) factors:
/// a dense border of the first `border` states, then chains of lumped masses, the border
/// coupled to the first and last node of each chain only. Every state is in the border or a
/// chain.
struct BlockStructure {
  int border = 0;
  std::vector<NodeChain> chains;
};

/// Thrown from inside a right-hand side when the state is not admissible (non-finite
/// value, zero-length segment): the integrator cuts the step and retries.
class RecoverableStateError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual int StateSize() const = 0;
  /// xdot = f(t, x). May throw RecoverableStateError.
  virtual void Derivatives(double t, const double* x, double* xdot) = 0;
  /// The pattern, fixed until the topology changes.
  virtual const SparsityPattern& JacobianPattern() const = 0;
  /// Values of df/dx in the order of JacobianPattern(); `xdot` is f(t, x), already known.
  virtual void Jacobian(double t, const double* x, const double* xdot, double* values) = 0;
  /// The Jacobian's block structure if it has one (fixed until the topology changes), for a
  /// structured linear solver; null means a general sparse LU.
  virtual const BlockStructure* Blocks() const { return nullptr; }
};

}  // namespace moorsim
