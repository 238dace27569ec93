#include "core/coupled_system.h"

#include <algorithm>

namespace moorsim {

CoupledSystem::CoupledSystem(BodyPlant& body, AttachedSubsystem& attached)
    : body_(body), attached_(attached) {
  Rebuild();
}

void CoupledSystem::Rebuild() {
  body_size_ = body_.StateSize();
  const std::span<const int> extra = body_.ExtraKinematicStates();
  extra_.assign(extra.begin(), extra.end());
  kinematic_columns_ = 12 + static_cast<int>(extra_.size());
  const SparsityPattern& sub = attached_.JacobianPattern();
  const int nb = body_size_;
  size_ = nb + sub.size;
  const int attachments = attached_.NumAttachments();
  const BlockStructure* sub_blocks = attached_.Blocks();
  has_blocks_ = sub_blocks != nullptr;
  // The subsystem's own border (its states first) joins the body's.
  blocks_.border = nb + (has_blocks_ ? sub_blocks->border : 0);
  blocks_.chains.clear();
  if (has_blocks_) {
    for (NodeChain chain : sub_blocks->chains) {
      chain.first_state += nb;
      blocks_.chains.push_back(chain);
    }
  }

  coupled_.clear();
  r_body_.resize(attachments);
  uncoupled_.clear();
  creep_.clear();
  for (int i = 0; i < attachments; ++i) {
    r_body_[i] = attached_.AttachmentPoint(i);
    if (const int creep = attached_.CouplingCreep(i); creep >= 0) creep_.push_back({i, creep});
    const int node = attached_.CouplingNode(i);
    if (node >= 0) {
      coupled_.push_back({i, node});
    } else if (attached_.Attached(i)) {
      uncoupled_.push_back(i);
    }
  }
  std::sort(coupled_.begin(), coupled_.end(),
            [](const Coupled& a, const Coupled& b) { return a.node_state < b.node_state; });

  std::sort(creep_.begin(), creep_.end(),
            [](const Creep& a, const Creep& b) { return a.state < b.state; });
  // The rows of the coupled nodes' accelerations (and of the creep the points pull) also
  // depend on eta and nu.
  std::vector<char> velocity_row_coupled(sub.size, 0);
  for (const Coupled& c : coupled_) {
    for (int k = 3; k < 6; ++k) velocity_row_coupled[c.node_state + k] = 1;
  }
  for (const Creep& c : creep_) velocity_row_coupled[c.state] = 1;

  pattern_.size = size_;
  pattern_.row_start.assign(1, 0);
  pattern_.column.clear();
  for (int r = 0; r < nb; ++r) {
    for (int col = 0; col < nb; ++col) pattern_.column.push_back(col);
    for (const Coupled& c : coupled_) {
      for (int k = 0; k < 6; ++k) pattern_.column.push_back(nb + c.node_state + k);
    }
    for (const Creep& c : creep_) pattern_.column.push_back(nb + c.state);
    pattern_.row_start.push_back(static_cast<int64_t>(pattern_.column.size()));
  }
  sub_row_destination_.resize(sub.size);
  for (int r = 0; r < sub.size; ++r) {
    if (velocity_row_coupled[r]) {
      for (int col = 0; col < 12; ++col) pattern_.column.push_back(col);
      for (const int col : extra_) pattern_.column.push_back(col);
    }
    sub_row_destination_[r] = static_cast<int64_t>(pattern_.column.size());
    for (int64_t j = sub.row_start[r]; j < sub.row_start[r + 1]; ++j) {
      pattern_.column.push_back(nb + static_cast<int>(sub.column[j]));
    }
    pattern_.row_start.push_back(static_cast<int64_t>(pattern_.column.size()));
  }

  points_.assign(attachments, PointKinematics{});
  point_jacobians_.assign(attachments, PointMotionJacobian{});
  forces_.assign(attachments, Vec3::Zero());
  loads_.assign(attachments, Vec6::Zero());
  sub_values_.assign(std::max<int64_t>(sub.nnz(), sub.size), 0.0);
  body_jacobian_.setZero(nb, nb);
  dtau_dnode_.assign(coupled_.size(), Mat6::Zero());
  daccel_dbody_.assign(coupled_.size(), BodyColumns3::Zero());
  dtau_dcreep_.assign(creep_.size(), Vec6::Zero());
  dcreep_dbody_.assign(creep_.size(), BodyColumns1::Zero());
  load_sensitivity_.setZero(nb, 6);
}

void CoupledSystem::ComputePoints(double t, const double* x, bool with_jacobian) {
  attached_.SetTime(t);
  for (std::size_t i = 0; i < points_.size(); ++i) {
    points_[i] =
        body_.PointMotion(t, x, r_body_[i], with_jacobian ? &point_jacobians_[i] : nullptr);
  }
}

void CoupledSystem::Derivatives(double t, const double* x, double* xdot) {
  const int nb = body_size_;
  ComputePoints(t, x, false);
  attached_.Derivatives(x + nb, points_, xdot + nb, forces_);
  tau_attached_.setZero();
  for (std::size_t i = 0; i < forces_.size(); ++i) {
    loads_[i] = body_.PointLoad(x, r_body_[i], forces_[i], nullptr);
    tau_attached_ += loads_[i];
  }
  body_.Derivatives(t, x, tau_attached_, xdot);
}

void CoupledSystem::Jacobian(double t, const double* x, const double* /*xdot*/, double* values) {
  const int nb = body_size_;
  const double* x_sub = x + nb;
  ComputePoints(t, x, true);
  // The forces at this state (the scratch derivative buffer is not needed afterwards).
  attached_.Derivatives(x_sub, points_, sub_values_.data(), forces_);

  Mat6 dtau_deta = Mat6::Zero();
  Mat6 dtau_dnu = Mat6::Zero();
  Eigen::Matrix<double, 6, kMaxExtraKinematicStates> dtau_dextra =
      Eigen::Matrix<double, 6, kMaxExtraKinematicStates>::Zero();
  const bool extra = !extra_.empty();
  tau_attached_.setZero();
  // Per coupled attachment: d tau / d(node r, v) and d a_node / d(eta, nu, extra).
  std::vector<Mat6>& dtau_dnode = dtau_dnode_;
  std::vector<BodyColumns3>& daccel_dbody = daccel_dbody_;
  const std::size_t coupled = coupled_.size();
  for (std::size_t ci = 0; ci < coupled; ++ci) {
    const int i = coupled_[ci].attachment;
    const PointMotionJacobian& P = point_jacobians_[i];
    PointLoadJacobian L;
    tau_attached_ += body_.PointLoad(x, r_body_[i], forces_[i], &L);
    const FairleadCoupling C = attached_.Coupling(x_sub, points_, i);
    const Eigen::Matrix<double, 3, 6> dF_deta =
        C.J_force_fairlead_pos * P.J_pos_eta + C.J_force_fairlead_vel * P.J_vel_eta;
    const Eigen::Matrix<double, 3, 6> dF_dnu = C.J_force_fairlead_vel * P.J_vel_nu;
    dtau_deta += L.J_load_eta + L.J_load_force * dF_deta;
    dtau_dnu += L.J_load_force * dF_dnu;
    dtau_dnode[ci].leftCols<3>() = L.J_load_force * C.J_force_node_pos;
    dtau_dnode[ci].rightCols<3>() = L.J_load_force * C.J_force_node_vel;
    daccel_dbody[ci].leftCols<6>() =
        C.J_accel_fairlead_pos * P.J_pos_eta + C.J_accel_fairlead_vel * P.J_vel_eta;
    daccel_dbody[ci].middleCols<6>(6) = C.J_accel_fairlead_vel * P.J_vel_nu;
    if (extra) {
      const ExtraColumns3 dF_dextra =
          C.J_force_fairlead_pos * P.J_pos_extra + C.J_force_fairlead_vel * P.J_vel_extra;
      dtau_dextra += L.J_load_extra + L.J_load_force * dF_dextra;
      daccel_dbody[ci].rightCols<kMaxExtraKinematicStates>() =
          C.J_accel_fairlead_pos * P.J_pos_extra + C.J_accel_fairlead_vel * P.J_vel_extra;
    }
  }
  // A creep stretch the fairlead force depends on, and which the point's position drives.
  for (std::size_t k = 0; k < creep_.size(); ++k) {
    const int i = creep_[k].attachment;
    const PointMotionJacobian& P = point_jacobians_[i];
    PointLoadJacobian L;
    body_.PointLoad(x, r_body_[i], forces_[i], &L);
    const FairleadCoupling C = attached_.Coupling(x_sub, points_, i);
    dtau_dcreep_[k] = L.J_load_force * C.J_force_creep;
    dcreep_dbody_[k].setZero();
    dcreep_dbody_[k].leftCols<6>() = C.J_creep_fairlead_pos * P.J_pos_eta;
    if (extra) {
      dcreep_dbody_[k].rightCols<kMaxExtraKinematicStates>() =
          C.J_creep_fairlead_pos * P.J_pos_extra;
    }
  }
  // Attachments without a free node (a one-segment chain) still load the body.
  for (const int i : uncoupled_) {
    PointLoadJacobian L;
    tau_attached_ += body_.PointLoad(x, r_body_[i], forces_[i], &L);
    dtau_deta += L.J_load_eta;
    if (extra) dtau_dextra += L.J_load_extra;
  }

  body_.Jacobian(t, x, tau_attached_, &body_jacobian_);
  body_.LoadSensitivity(x, tau_attached_, &load_sensitivity_);
  body_jacobian_.leftCols<6>() += load_sensitivity_ * dtau_deta;
  body_jacobian_.middleCols<6>(6) += load_sensitivity_ * dtau_dnu;
  for (std::size_t j = 0; j < extra_.size(); ++j) {
    body_jacobian_.col(extra_[j]) += load_sensitivity_ * dtau_dextra.col(static_cast<int>(j));
  }

  double* v = values;
  for (int r = 0; r < nb; ++r) {
    for (int col = 0; col < nb; ++col) *v++ = body_jacobian_(r, col);
    for (std::size_t ci = 0; ci < coupled; ++ci) {
      const Eigen::Matrix<double, 1, 6> row = load_sensitivity_.row(r) * dtau_dnode[ci];
      for (int k = 0; k < 6; ++k) *v++ = row(k);
    }
    for (const Vec6& d : dtau_dcreep_) *v++ = load_sensitivity_.row(r).dot(d);
  }

  const SparsityPattern& sub = attached_.JacobianPattern();
  attached_.Jacobian(x_sub, points_, sub_values_.data());
  for (int r = 0; r < sub.size; ++r) {
    const int64_t count = sub.row_start[r + 1] - sub.row_start[r];
    std::copy_n(sub_values_.data() + sub.row_start[r], count, values + sub_row_destination_[r]);
  }
  const int kinematic = kinematic_columns_;
  for (std::size_t ci = 0; ci < coupled; ++ci) {
    for (int k = 0; k < 3; ++k) {
      double* row = values + sub_row_destination_[coupled_[ci].node_state + 3 + k] - kinematic;
      for (int col = 0; col < kinematic; ++col) row[col] = daccel_dbody[ci](k, col);
    }
  }
  for (std::size_t k = 0; k < creep_.size(); ++k) {
    double* row = values + sub_row_destination_[creep_[k].state] - kinematic;
    for (int col = 0; col < kinematic; ++col) row[col] = dcreep_dbody_[k](col);
  }
}

}  // namespace moorsim
