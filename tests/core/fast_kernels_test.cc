// The replacement vector and sparse-matrix kernels against SUNDIALS' own on random data,
// including aliased arguments and the fall-back paths.
#include "core/fast_kernels.h"

#include <gtest/gtest.h>
#include <sundials/sundials_context.h>

#include <random>
#include <vector>

namespace moorsim::internal {
namespace {

class FastKernels : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(SUNContext_Create(internal::kNoCommunicator, &ctx_), 0); }
  void TearDown() override {
    for (N_Vector v : vectors_) N_VDestroy(v);
    for (SUNMatrix m : matrices_) SUNMatDestroy(m);
    SUNContext_Free(&ctx_);
  }
  // A plain library vector and a fast one holding the same random values.
  std::pair<N_Vector, N_Vector> Pair(int n) {
    N_Vector plain = N_VNew_Serial(n, ctx_);
    N_Vector fast = N_VNew_Serial(n, ctx_);
    InstallFastSerialOps(fast);
    for (int i = 0; i < n; ++i) {
      NV_Ith_S(plain, i) = NV_Ith_S(fast, i) = dist_(rng_) + 0.1 * (i % 7);
    }
    vectors_.push_back(plain);
    vectors_.push_back(fast);
    return {plain, fast};
  }
  static void ExpectSame(N_Vector a, N_Vector b) {
    for (sunindextype i = 0; i < N_VGetLength(a); ++i) {
      // Element-wise arithmetic in the same order: identical up to fused multiply-add.
      EXPECT_NEAR(NV_Ith_S(a, i), NV_Ith_S(b, i), 1e-15 * (1.0 + std::abs(NV_Ith_S(a, i))));
    }
  }

  SUNContext ctx_ = nullptr;
  std::mt19937 rng_{3};
  std::uniform_real_distribution<double> dist_{0.5, 2.0};
  std::vector<N_Vector> vectors_;
  std::vector<SUNMatrix> matrices_;
};

TEST_F(FastKernels, VectorOperationsMatchTheLibrary) {
  const int n = 1003;  // not a multiple of any SIMD width or block size
  auto [x0, x1] = Pair(n);
  auto [y0, y1] = Pair(n);
  auto [z0, z1] = Pair(n);
  N_VLinearSum(1.5, x0, -0.25, y0, z0);
  N_VLinearSum(1.5, x1, -0.25, y1, z1);
  ExpectSame(z0, z1);
  N_VLinearSum(2.0, z0, 3.0, y0, z0);  // output aliases an input
  N_VLinearSum(2.0, z1, 3.0, y1, z1);
  ExpectSame(z0, z1);
  N_VScale(-3.0, x0, z0);
  N_VScale(-3.0, x1, z1);
  ExpectSame(z0, z1);
  N_VProd(x0, y0, z0);
  N_VProd(x1, y1, z1);
  ExpectSame(z0, z1);
  N_VDiv(x0, y0, z0);
  N_VDiv(x1, y1, z1);
  ExpectSame(z0, z1);
  N_VInv(z0, z0);
  N_VInv(z1, z1);
  ExpectSame(z0, z1);
  N_VAddConst(x0, 0.7, z0);
  N_VAddConst(x1, 0.7, z1);
  ExpectSame(z0, z1);
  N_VScale(-1.0, z0, z0);
  N_VScale(-1.0, z1, z1);
  N_VAbs(z0, z0);
  N_VAbs(z1, z1);
  ExpectSame(z0, z1);
  N_VConst(4.25, z0);
  N_VConst(4.25, z1);
  ExpectSame(z0, z1);
  // The norm sums in a different order: equal to round-off.
  EXPECT_NEAR(N_VWrmsNorm(x0, y0), N_VWrmsNorm(x1, y1), 1e-14 * N_VWrmsNorm(x0, y0));
}

TEST_F(FastKernels, FusedOperationsMatchTheLibraryWithAliasing) {
  const int n = 777;
  auto [a0, a1] = Pair(n);
  auto [b0, b1] = Pair(n);
  auto [c0, c1] = Pair(n);
  auto [z0, z1] = Pair(n);
  N_VEnableFusedOps_Serial(a0, SUNTRUE);
  N_VEnableFusedOps_Serial(z0, SUNTRUE);
  sunrealtype coef[4] = {0.5, -1.25, 2.0, 0.125};
  // z = 0.5 z - 1.25 a + 2 b + 0.125 c, with z itself as the first term.
  N_Vector plain[4] = {z0, a0, b0, c0};
  N_Vector fast[4] = {z1, a1, b1, c1};
  ASSERT_EQ(N_VLinearCombination(4, coef, plain, z0), 0);
  ASSERT_EQ(N_VLinearCombination(4, coef, fast, z1), 0);
  ExpectSame(z0, z1);
  // Z[i] = a[i] x + Y[i] with Z = Y.
  N_Vector ys0[2] = {b0, c0};
  N_Vector ys1[2] = {b1, c1};
  ASSERT_EQ(N_VScaleAddMulti(2, coef, a0, ys0, ys0), 0);
  ASSERT_EQ(N_VScaleAddMulti(2, coef, a1, ys1, ys1), 0);
  ExpectSame(b0, b1);
  ExpectSame(c0, c1);
  // Z[i] = c[i] X[i], in place as CVODE rescales its history.
  N_Vector xs0[2] = {b0, c0};
  N_Vector xs1[2] = {b1, c1};
  ASSERT_EQ(N_VScaleVectorArray(2, coef + 1, xs0, xs0), 0);
  ASSERT_EQ(N_VScaleVectorArray(2, coef + 1, xs1, xs1), 0);
  ExpectSame(b0, b1);
  ExpectSame(c0, c1);
}

// A random n x n CSR matrix: a band of width 3 around the diagonal, the diagonal itself
// left out in row `skip_diagonal` (or none if -1).
SUNMatrix RandomCsr(int n, int skip_diagonal, SUNContext ctx, std::mt19937& rng) {
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  SUNMatrix m = SUNSparseMatrix(n, n, 7 * n, CSR_MAT, ctx);
  sunindextype* start = SUNSparseMatrix_IndexPointers(m);
  sunindextype* index = SUNSparseMatrix_IndexValues(m);
  double* data = SUNSparseMatrix_Data(m);
  sunindextype k = 0;
  for (int r = 0; r < n; ++r) {
    start[r] = k;
    for (int c = std::max(0, r - 3); c <= std::min(n - 1, r + 3); ++c) {
      if (c == r && r == skip_diagonal) continue;
      index[k] = c;
      data[k++] = dist(rng);
    }
  }
  start[n] = k;
  return m;
}

void ExpectSameMatrix(SUNMatrix a, SUNMatrix b) {
  const sunindextype np = SUNSparseMatrix_NP(a);
  ASSERT_EQ(SUNSparseMatrix_IndexPointers(a)[np], SUNSparseMatrix_IndexPointers(b)[np]);
  for (sunindextype j = 0; j <= np; ++j) {
    ASSERT_EQ(SUNSparseMatrix_IndexPointers(a)[j], SUNSparseMatrix_IndexPointers(b)[j]);
  }
  for (sunindextype k = 0; k < SUNSparseMatrix_IndexPointers(a)[np]; ++k) {
    ASSERT_EQ(SUNSparseMatrix_IndexValues(a)[k], SUNSparseMatrix_IndexValues(b)[k]);
    ASSERT_DOUBLE_EQ(SUNSparseMatrix_Data(a)[k], SUNSparseMatrix_Data(b)[k]);
  }
}

TEST_F(FastKernels, SparseMatrixOperationsMatchTheLibrary) {
  for (int skip : {-1, 17}) {  // with every diagonal, and with one missing (fall-back)
    std::mt19937 rng_a(11), rng_b(11);
    SUNMatrix plain = RandomCsr(40, skip, ctx_, rng_a);
    SUNMatrix fast = RandomCsr(40, skip, ctx_, rng_b);
    InstallFastSparseOps(fast);
    matrices_.push_back(plain);
    matrices_.push_back(fast);
    ExpectSameMatrix(plain, fast);

    ASSERT_EQ(SUNMatScaleAddI(-0.3, plain), 0);
    ASSERT_EQ(SUNMatScaleAddI(-0.3, fast), 0);
    ExpectSameMatrix(plain, fast);

    SUNMatrix plain_copy = SUNMatClone(plain);
    SUNMatrix fast_copy = SUNMatClone(fast);  // the clone has the fast operations too
    matrices_.push_back(plain_copy);
    matrices_.push_back(fast_copy);
    EXPECT_EQ(fast_copy->ops->copy, fast->ops->copy);
    ASSERT_EQ(SUNMatCopy(plain, plain_copy), 0);
    ASSERT_EQ(SUNMatCopy(fast, fast_copy), 0);
    ExpectSameMatrix(plain_copy, fast_copy);
    ExpectSameMatrix(plain, fast_copy);

    ASSERT_EQ(SUNMatZero(plain_copy), 0);
    ASSERT_EQ(SUNMatZero(fast_copy), 0);
    ExpectSameMatrix(plain_copy, fast_copy);
  }
}

}  // namespace
}  // namespace moorsim::internal
