// What every user of the HDF5 library in this module does before its first HDF5 call.
#pragma once

namespace moorsim::output::internal {

/// Switches off HDF5's printing of error stacks in the calling thread (the failure goes
/// into an exception instead) and, on the first call of the process, HDF5's exit-time
/// cleanup: HDF5 1.10 crashes in it after a file's close has failed (a full disk). Call it
/// before the process's first HDF5 call; afterwards the exit-time part is a no-op.
void PrepareHdf5();

}  // namespace moorsim::output::internal
