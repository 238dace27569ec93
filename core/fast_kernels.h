// Faster serial N_Vector and sparse SUNMatrix operations for CVODE.
//
// Debian's SUNDIALS build runs its serial vector kernels at 14-20 instructions per element
// (callgrind, seed mooring): N_VLinearSum alone was 21 % of a simulate-lines run, and the
// sparse matrix copy / zero / scale-add-identity of each linear-solver setup another 16 %.
// These replacements do the same arithmetic (Eigen array expressions, memcpy/memset) and
// are installed in the objects' operation tables; clones inherit them. Each is checked
// against the library's own operation in tests/core/fast_kernels_test.cc.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sunmatrix/sunmatrix_sparse.h>

namespace moorsim::internal {

/// The communicator argument of SUNContext_Create for a serial run: a null pointer in
/// SUNDIALS 6, SUN_COMM_NULL (SUNComm) from SUNDIALS 7 on.
#if SUNDIALS_VERSION_MAJOR >= 7
inline const SUNComm kNoCommunicator = SUN_COMM_NULL;
#else
inline void* const kNoCommunicator = nullptr;
#endif

/// Replaces the hot operations of a serial N_Vector (linear sum, scale, constant, fused
/// linear combination and scale-add, weighted RMS norm, element-wise products).
void InstallFastSerialOps(N_Vector v);

/// Replaces zero, copy, scale-add-identity and clone of a sparse SUNMatrix. Copy and
/// scale-add-identity fall back to the library when they would need to reallocate (a
/// target too small, a missing diagonal entry).
void InstallFastSparseOps(SUNMatrix m);

}  // namespace moorsim::internal
