// The mooring lines as the attached subsystem of the coupled simulation
// (core/coupled_system.h): one attachment per line, at its body-frame fairlead (a line
// between free points, or up to one, never loads the vessel: not Attached()).
#pragma once

#include "core/coupled_system.h"
#include "mooring_fem/mooring_system.h"

namespace moorsim::mooring_fem {

class MooringAttachment final : public AttachedSubsystem {
 public:
  explicit MooringAttachment(MooringSystem& mooring) : mooring_(mooring) {}

  int StateSize() const override { return mooring_.StateSize(); }
  const SparsityPattern& JacobianPattern() const override { return mooring_.JacobianPattern(); }
  const BlockStructure* Blocks() const override {
    return mooring_.has_blocks() ? &mooring_.Blocks() : nullptr;
  }
  int NumAttachments() const override { return mooring_.num_lines(); }
  Vec3 AttachmentPoint(int i) const override { return mooring_.line(i).fairlead_body; }
  bool Attached(int i) const override { return mooring_.at_vessel(i); }
  int CouplingNode(int i) const override { return mooring_.CouplingNode(i); }
  int CouplingCreep(int i) const override { return mooring_.CouplingCreep(i); }
  void SetTime(double t) override { mooring_.SetTime(t); }
  void Derivatives(const double* x, std::span<const PointKinematics> points, double* xdot,
                   std::span<Vec3> forces) override {
    mooring_.Derivatives(x, points, xdot, forces);
  }
  void Jacobian(const double* x, std::span<const PointKinematics> points, double* values) override {
    mooring_.Jacobian(x, points, values);
  }
  FairleadCoupling Coupling(const double* x, std::span<const PointKinematics> points,
                            int i) override {
    return mooring_.FairleadJacobian(x, points, i);
  }

 private:
  MooringSystem& mooring_;
};

}  // namespace moorsim::mooring_fem
