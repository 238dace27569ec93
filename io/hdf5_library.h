// What every user of the HDF5 library in this module shares: the preparation before the
// first HDF5 call, and the owner of an HDF5 identifier.
#pragma once

#include <hdf5.h>

#include <utility>

namespace moorsim::output::internal {

/// Switches off HDF5's printing of error stacks in the calling thread (the failure goes
/// into an exception instead) and, on the first call of the process, HDF5's exit-time
/// cleanup: HDF5 1.10 crashes in it after a file's close has failed (a full disk). Call it
/// before the process's first HDF5 call; afterwards the exit-time part is a no-op.
void PrepareHdf5();

/// Owns one HDF5 identifier and closes it with the matching H5?close call.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);

  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      Close();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { Close(); }

  hid_t get() const { return id_; }

  /// Closes the identifier now; returns the close call's status (0 if nothing was open).
  herr_t Close() {
    if (id_ < 0) return 0;
    const herr_t status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

}  // namespace moorsim::output::internal
