// The monolithic coupling of a rigid body (the vessel) with subsystems attached to points on
// it (the mooring lines), as one OdeSystem for one CVODE instance (docs/design.md section 4).
//
// State layout: [body states (eta, nu, then the body's own extra states such as thrust),
// attached-subsystem states]. Kinematics in, forces out: the body tells where each
// attachment point is and how fast it moves; the subsystem returns the force it exerts on
// the body at each point (Earth frame) and its own derivatives. The assembler sums the
// attachment loads into the body's equations and builds the Jacobian from the parts' own
// analytic blocks:
//
//   body rows      d f_b/d x_b  = B_b + S (dtau/deta, dtau/dnu)      (S = d f_b / d tau)
//                  d f_b/d node = S dtau/dF dF/d(node n-1)
//   node rows      d a_{n-1}/d(eta, nu) = J_accel_fairlead_* d(point kinematics)/d(eta, nu)
//
// and likewise for the body's extra kinematic states (a turret's angle and rate, which move
// the points), which then join eta and nu in the columns of the coupled nodes' rows.
//
// with dtau/deta, dtau/dnu from the attachment forces' dependence on the point's position
// and velocity, and from the rotation of an Earth-frame force into body axes. The pattern is
// the subsystem's own (shifted by the body's size) plus a dense body block, the coupled
// nodes' columns in the body rows and the body's eta/nu columns in the coupled nodes' rows.
// It is rebuilt by Rebuild() when the subsystem's topology changes.
#pragma once

#include <span>
#include <vector>

#include "core/ode_system.h"
#include "core/types.h"

namespace moorsim {

/// At most this many body states besides eta and nu move the attachment points (a turret's
/// angle and rate of turn: BodyPlant::ExtraKinematicStates()).
inline constexpr int kMaxExtraKinematicStates = 2;
using ExtraColumns3 = Eigen::Matrix<double, 3, kMaxExtraKinematicStates>;

/// Derivatives of a body point's Earth-frame kinematics with respect to the body's
/// pose eta and velocity nu (the first 12 body states) and its extra kinematic states (in
/// the order of BodyPlant::ExtraKinematicStates(); unused columns zero).
struct PointMotionJacobian {
  Eigen::Matrix<double, 3, 6> J_pos_eta = Eigen::Matrix<double, 3, 6>::Zero();
  Eigen::Matrix<double, 3, 6> J_vel_eta = Eigen::Matrix<double, 3, 6>::Zero();
  Eigen::Matrix<double, 3, 6> J_vel_nu = Eigen::Matrix<double, 3, 6>::Zero();
  ExtraColumns3 J_pos_extra = ExtraColumns3::Zero();
  ExtraColumns3 J_vel_extra = ExtraColumns3::Zero();
};

/// The body-frame load of an Earth-frame force at a body point, and its derivatives.
struct PointLoadJacobian {
  Eigen::Matrix<double, 6, 3> J_load_force = Eigen::Matrix<double, 6, 3>::Zero();
  Mat6 J_load_eta = Mat6::Zero();  ///< through the rotation Earth -> body, force held
  /// Through the point's dependence on the extra kinematic states, force held.
  Eigen::Matrix<double, 6, kMaxExtraKinematicStates> J_load_extra =
      Eigen::Matrix<double, 6, kMaxExtraKinematicStates>::Zero();
};

/// The derivatives that couple a subsystem to the body through one attachment point: the
/// subsystem's last free node (n-1) feels the point's position and velocity, and the force
/// on the body depends on that node and on the point itself.
struct FairleadCoupling {
  int node_state = -1;  ///< index of node n-1's first state component (r, then v); -1 none
  Mat3 J_accel_fairlead_pos = Mat3::Zero();  ///< d a_{n-1} / d r_n
  Mat3 J_accel_fairlead_vel = Mat3::Zero();  ///< d a_{n-1} / d v_n
  Mat3 J_force_node_pos = Mat3::Zero();      ///< d F_fairlead / d r_{n-1}
  Mat3 J_force_node_vel = Mat3::Zero();      ///< d F_fairlead / d v_{n-1}
  Mat3 J_force_fairlead_pos = Mat3::Zero();  ///< d F_fairlead / d r_n
  Mat3 J_force_fairlead_vel = Mat3::Zero();  ///< d F_fairlead / d v_n (acceleration held)
  /// A state of the subsystem besides the node's that the fairlead force depends on and that
  /// depends on the point's position (a visco-elastic top segment's creep stretch), or -1.
  int creep_state = -1;
  Vec3 J_force_creep = Vec3::Zero();                                     ///< d F_fairlead / d creep
  Eigen::RowVector3d J_creep_fairlead_pos = Eigen::RowVector3d::Zero();  ///< d creep' / d r_n
};

/// The rigid body: states [eta (6), nu (6), extra...].
class BodyPlant {
 public:
  virtual ~BodyPlant() = default;
  virtual int StateSize() const = 0;
  /// Indices (ascending, >= 12) of the extra states the attachment points move with besides
  /// eta and nu (a turret's angle and rate), at most kMaxExtraKinematicStates.
  virtual std::span<const int> ExtraKinematicStates() const { return {}; }
  /// xdot of the body's states under the attachment load tau_attached (body frame).
  virtual void Derivatives(double t, const double* x, const Vec6& tau_attached, double* xdot) = 0;
  /// d xdot / d x of the body's own states (StateSize x StateSize), tau_attached held.
  virtual void Jacobian(double t, const double* x, const Vec6& tau_attached, MatX* J) = 0;
  /// d xdot / d tau_attached (StateSize x 6) at tau_attached.
  virtual void LoadSensitivity(const double* x, const Vec6& tau_attached,
                               Eigen::Matrix<double, Eigen::Dynamic, 6>* S) = 0;
  /// Earth-frame position and velocity of the attachment point r_body [m] (body frame, as
  /// AttachedSubsystem::AttachmentPoint gives it; the body may move it, e.g. on a turret)
  /// at time t (acceleration left zero) and, if J is given, their derivatives with respect
  /// to eta, nu and the extra kinematic states.
  virtual PointKinematics PointMotion(double t, const double* x, const Vec3& r_body,
                                      PointMotionJacobian* J) = 0;
  /// Body-frame load [N, N m] about the body origin of the Earth-frame force F at the
  /// attachment point r_body (where PointMotion puts it).
  virtual Vec6 PointLoad(const double* x, const Vec3& r_body, const Vec3& F,
                         PointLoadJacobian* J) = 0;
};

/// Something attached to body points: it has its own states and sparse Jacobian.
class AttachedSubsystem {
 public:
  virtual ~AttachedSubsystem() = default;
  virtual int StateSize() const = 0;
  virtual const SparsityPattern& JacobianPattern() const = 0;
  virtual int NumAttachments() const = 0;
  /// Body-frame position of attachment i [m].
  virtual Vec3 AttachmentPoint(int i) const = 0;
  /// Whether attachment i still transmits force (a parted line does not).
  virtual bool Attached(int i) const = 0;
  /// The time the next Derivatives, Jacobian and Coupling calls are at (for a subsystem
  /// whose forces depend on time, e.g. lines in waves). The coupled system sets it first.
  virtual void SetTime(double /*t*/) {}
  /// Own derivatives and the Earth-frame force on the body at every attachment (zero for
  /// detached ones) for the given point kinematics.
  virtual void Derivatives(const double* x, std::span<const PointKinematics> points, double* xdot,
                           std::span<Vec3> forces) = 0;
  /// Own Jacobian values in JacobianPattern() order, points held.
  virtual void Jacobian(const double* x, std::span<const PointKinematics> points,
                        double* values) = 0;
  /// Index of the state of the node coupled to attachment i (its first component, in this
  /// subsystem's numbering), or -1 if the attachment is detached or has no free node.
  virtual int CouplingNode(int i) const = 0;
  /// FairleadCoupling::creep_state of attachment i, fixed per topology (-1: none).
  virtual int CouplingCreep(int /*i*/) const { return -1; }
  /// Coupling blocks of attachment i (which must be attached).
  virtual FairleadCoupling Coupling(const double* x, std::span<const PointKinematics> points,
                                    int i) = 0;
  /// The block structure of JacobianPattern() (chains coupled to the body through their last
  /// node, CouplingNode()), or null if it has none.
  virtual const BlockStructure* Blocks() const { return nullptr; }
};

class CoupledSystem : public OdeSystem {
 public:
  CoupledSystem(BodyPlant& body, AttachedSubsystem& attached);

  /// Re-reads the parts' sizes and patterns (after a topology change of the subsystem).
  void Rebuild();

  int StateSize() const override { return size_; }
  void Derivatives(double t, const double* x, double* xdot) override;
  const SparsityPattern& JacobianPattern() const override { return pattern_; }
  /// The body and the subsystem's own border (its first states) as the border, the
  /// subsystem's chains after them (if it has a structure).
  const BlockStructure* Blocks() const override { return has_blocks_ ? &blocks_ : nullptr; }
  void Jacobian(double t, const double* x, const double* xdot, double* values) override;

  int body_size() const { return body_size_; }
  /// Attachment kinematics and forces of the last Derivatives() call.
  std::span<const PointKinematics> points() const { return points_; }
  std::span<const Vec3> forces() const { return forces_; }
  /// Attachment load on the body of the last Derivatives() call (body frame).
  const Vec6& attachment_load() const { return tau_attached_; }
  /// Per attachment, the body-frame load of the last Derivatives() call.
  std::span<const Vec6> attachment_loads() const { return loads_; }

 private:
  void ComputePoints(double t, const double* x, bool with_jacobian);

  BodyPlant& body_;
  AttachedSubsystem& attached_;
  int body_size_ = 0;
  int size_ = 0;
  SparsityPattern pattern_;
  BlockStructure blocks_;
  bool has_blocks_ = false;
  // Copy plan for the subsystem's Jacobian rows: for subsystem row i, the slot in the
  // combined values where its own entries start.
  std::vector<int64_t> sub_row_destination_;
  // Attachments whose coupling node exists, in increasing node order (columns of the body
  // rows after the body's own).
  struct Coupled {
    int attachment;
    int node_state;  // in the subsystem's numbering
  };
  std::vector<Coupled> coupled_;
  // Attached, but with no free node to couple (a one-segment chain): load only.
  std::vector<int> uncoupled_;
  // Attachments whose force depends on a creep state, in increasing state order (columns of
  // the body rows after the coupled nodes').
  struct Creep {
    int attachment;
    int state;  // in the subsystem's numbering
  };
  std::vector<Creep> creep_;

  // Scratch.
  std::vector<Vec3> r_body_;
  std::vector<PointKinematics> points_;
  std::vector<PointMotionJacobian> point_jacobians_;
  std::vector<Vec3> forces_;
  std::vector<Vec6> loads_;
  std::vector<double> sub_values_;
  std::vector<Mat6> dtau_dnode_;
  // d a_node / d(eta, nu, extra kinematic states).
  using BodyColumns3 = Eigen::Matrix<double, 3, 12 + kMaxExtraKinematicStates>;
  std::vector<BodyColumns3> daccel_dbody_;
  // Per creep-coupled attachment: d tau / d creep and d creep' / d(eta, nu, extra).
  using BodyColumns1 = Eigen::Matrix<double, 1, 12 + kMaxExtraKinematicStates>;
  std::vector<Vec6> dtau_dcreep_;
  std::vector<BodyColumns1> dcreep_dbody_;
  std::vector<int> extra_;      // the body's extra kinematic states
  int kinematic_columns_ = 12;  // 12 + extra_.size()
  MatX body_jacobian_;
  Eigen::Matrix<double, Eigen::Dynamic, 6> load_sensitivity_;
  Vec6 tau_attached_ = Vec6::Zero();
};

}  // namespace moorsim
