#include "core/fast_kernels.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace moorsim::internal {
namespace {

using Array = Eigen::Map<Eigen::ArrayXd>;

// Every operation is element-wise, so an output that aliases an input is safe: each
// element is read before it is written and no other element depends on it.
Array A(N_Vector v) { return Array(N_VGetArrayPointer_Serial(v), N_VGetLength_Serial(v)); }

void LinearSum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  A(z) = a * A(x) + b * A(y);
}
void Const(sunrealtype c, N_Vector z) { A(z).setConstant(c); }
void Prod(N_Vector x, N_Vector y, N_Vector z) { A(z) = A(x) * A(y); }
void Div(N_Vector x, N_Vector y, N_Vector z) { A(z) = A(x) / A(y); }
void Scale(sunrealtype c, N_Vector x, N_Vector z) { A(z) = c * A(x); }
void Abs(N_Vector x, N_Vector z) { A(z) = A(x).abs(); }
void Inv(N_Vector x, N_Vector z) { A(z) = A(x).inverse(); }
void AddConst(N_Vector x, sunrealtype b, N_Vector z) { A(z) = A(x) + b; }

sunrealtype WrmsNorm(N_Vector x, N_Vector w) {
  const double n = static_cast<double>(N_VGetLength_Serial(x));
  return std::sqrt((A(x) * A(w)).square().sum() / n);
}

// z = sum_i c[i] X[i]. z may be one of the X[i], so accumulate element-major in blocks.
int LinearCombination(int nvec, sunrealtype* c, N_Vector* X, N_Vector z) {
  const sunindextype n = N_VGetLength_Serial(z);
  double* out = N_VGetArrayPointer_Serial(z);
  constexpr sunindextype kBlock = 256;
  double acc[kBlock];
  for (sunindextype start = 0; start < n; start += kBlock) {
    const sunindextype len = std::min(kBlock, n - start);
    Eigen::Map<Eigen::ArrayXd> a(acc, len);
    a = c[0] * Eigen::Map<const Eigen::ArrayXd>(N_VGetArrayPointer_Serial(X[0]) + start, len);
    for (int i = 1; i < nvec; ++i) {
      a += c[i] * Eigen::Map<const Eigen::ArrayXd>(N_VGetArrayPointer_Serial(X[i]) + start, len);
    }
    Eigen::Map<Eigen::ArrayXd>(out + start, len) = a;
  }
  return 0;
}

// Z[i] = a[i] x + Y[i]; Z[i] may be Y[i].
int ScaleAddMulti(int nvec, sunrealtype* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) A(Z[i]) = a[i] * A(x) + A(Y[i]);
  return 0;
}

// Z[i] = c[i] X[i] (CVODE rescales its history with it at every step-size change).
int ScaleVectorArray(int nvec, sunrealtype* c, N_Vector* X, N_Vector* Z) {
  for (int i = 0; i < nvec; ++i) A(Z[i]) = c[i] * A(X[i]);
  return 0;
}

int SparseZero(SUNMatrix m) {
  const sunindextype nnz = SUNSparseMatrix_NNZ(m);
  std::memset(SUNSparseMatrix_Data(m), 0, nnz * sizeof(sunrealtype));
  std::memset(SUNSparseMatrix_IndexValues(m), 0, nnz * sizeof(sunindextype));
  std::memset(SUNSparseMatrix_IndexPointers(m), 0,
              (SUNSparseMatrix_NP(m) + 1) * sizeof(sunindextype));
  return SUNMAT_SUCCESS;
}

bool SameShape(SUNMatrix a, SUNMatrix b) {
  return SUNMatGetID(b) == SUNMATRIX_SPARSE && SUNSparseMatrix_Rows(a) == SUNSparseMatrix_Rows(b) &&
         SUNSparseMatrix_Columns(a) == SUNSparseMatrix_Columns(b) &&
         SUNSparseMatrix_SparseType(a) == SUNSparseMatrix_SparseType(b);
}

// B = A (pattern and values).
int SparseCopy(SUNMatrix a, SUNMatrix b) {
  const sunindextype np = SUNSparseMatrix_NP(a);
  const sunindextype nz = SUNSparseMatrix_IndexPointers(a)[np];
  if (!SameShape(a, b) || SUNSparseMatrix_NNZ(b) < nz) return SUNMatCopy_Sparse(a, b);
  const sunindextype capacity = SUNSparseMatrix_NNZ(b);
  std::memcpy(SUNSparseMatrix_Data(b), SUNSparseMatrix_Data(a), nz * sizeof(sunrealtype));
  std::memcpy(SUNSparseMatrix_IndexValues(b), SUNSparseMatrix_IndexValues(a),
              nz * sizeof(sunindextype));
  std::memset(SUNSparseMatrix_Data(b) + nz, 0, (capacity - nz) * sizeof(sunrealtype));
  std::memset(SUNSparseMatrix_IndexValues(b) + nz, 0, (capacity - nz) * sizeof(sunindextype));
  std::memcpy(SUNSparseMatrix_IndexPointers(b), SUNSparseMatrix_IndexPointers(a),
              (np + 1) * sizeof(sunindextype));
  return SUNMAT_SUCCESS;
}

// Position of the diagonal entry of row (CSR) or column (CSC) j, or -1.
sunindextype Diagonal(const sunindextype* start, const sunindextype* index, sunindextype j) {
  for (sunindextype k = start[j]; k < start[j + 1]; ++k) {
    if (index[k] == j) return k;
  }
  return -1;
}

// A = c A + I.
int SparseScaleAddI(sunrealtype c, SUNMatrix m) {
  const sunindextype* start = SUNSparseMatrix_IndexPointers(m);
  const sunindextype* index = SUNSparseMatrix_IndexValues(m);
  const sunindextype n = std::min(SUNSparseMatrix_Rows(m), SUNSparseMatrix_Columns(m));
  const sunindextype np = SUNSparseMatrix_NP(m);
  for (sunindextype j = 0; j < n; ++j) {
    if (j >= np || Diagonal(start, index, j) < 0) return SUNMatScaleAddI_Sparse(c, m);
  }
  double* data = SUNSparseMatrix_Data(m);
  Eigen::Map<Eigen::ArrayXd>(data, start[np]) *= c;
  for (sunindextype j = 0; j < n; ++j) data[Diagonal(start, index, j)] += 1.0;
  return SUNMAT_SUCCESS;
}

SUNMatrix SparseClone(SUNMatrix m) {
  SUNMatrix clone = SUNMatClone_Sparse(m);
  if (clone != nullptr) InstallFastSparseOps(clone);
  return clone;
}

}  // namespace

void InstallFastSparseOps(SUNMatrix m) {
  m->ops->zero = &SparseZero;
  m->ops->copy = &SparseCopy;
  m->ops->scaleaddi = &SparseScaleAddI;
  m->ops->clone = &SparseClone;
}

void InstallFastSerialOps(N_Vector v) {
  N_VEnableFusedOps_Serial(v, SUNTRUE);
  v->ops->nvlinearsum = &LinearSum;
  v->ops->nvconst = &Const;
  v->ops->nvprod = &Prod;
  v->ops->nvdiv = &Div;
  v->ops->nvscale = &Scale;
  v->ops->nvabs = &Abs;
  v->ops->nvinv = &Inv;
  v->ops->nvaddconst = &AddConst;
  v->ops->nvwrmsnorm = &WrmsNorm;
  v->ops->nvlinearcombination = &LinearCombination;
  v->ops->nvscaleaddmulti = &ScaleAddMulti;
  v->ops->nvscalevectorarray = &ScaleVectorArray;
}

}  // namespace moorsim::internal
