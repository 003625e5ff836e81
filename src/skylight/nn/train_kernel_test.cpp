#include "skylight/nn/detail/train_kernel.h"

#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <span>
#include <vector>

#include "skylight/nn/random.h"

namespace skylight::nn::detail {
namespace {

// The kernel's sums of <= 300 products of O(1) numbers differ from the naive order by a few ulps
// of the sum's magnitude (~1e-16 x 300).
constexpr double kGemmTolerance = 1e-12;

TEST(GemmAbt, MatchesNaiveProductOnOddSizes) {
  const std::size_t pad = gemm_abt_row_padding();
  Rng rng(1);
  for (std::size_t m : {1u, 5u, 17u, 40u}) {
    for (std::size_t n : {1u, 3u, 4u, 9u}) {
      for (std::size_t depth : {1u, 7u, 300u}) {
        const std::size_t lda = (m + pad - 1) / pad * pad + pad, ldb = n + 2, ldc = m + 1;
        std::vector<double> A(lda * depth), B(ldb * depth), C(ldc * n), ref(ldc * n);
        for (auto& v : A) v = rng.uniform(-1.0, 1.0);
        for (auto& v : B) v = rng.uniform(-1.0, 1.0);
        for (std::size_t k = 0; k < C.size(); ++k) C[k] = ref[k] = rng.uniform(-1.0, 1.0);
        for (std::size_t j = 0; j < n; ++j) {
          for (std::size_t i = 0; i < m; ++i) {
            for (std::size_t k = 0; k < depth; ++k)
              ref[i + j * ldc] += A[i + k * lda] * B[j + k * ldb];
          }
        }
        gemm_abt(A.data(), lda, B.data(), ldb, m, n, depth, C.data(), ldc, false);
        for (std::size_t j = 0; j < n; ++j) {
          for (std::size_t i = 0; i < ldc; ++i) {
            // Row m of each column (i == m) is outside C: it must be left untouched.
            EXPECT_NEAR(C[i + j * ldc], ref[i + j * ldc], kGemmTolerance)
                << m << "x" << n << "x" << depth << " at " << i << "," << j;
          }
        }
      }
    }
  }
}

TEST(GemmAbt, LowerTriangleOfASymmetricUpdate) {
  const std::size_t pad = gemm_abt_row_padding();
  const std::size_t m = 23, depth = 50, lda = (m + pad - 1) / pad * pad;
  Rng rng(2);
  std::vector<double> A(lda * depth), C(m * m, 0.0);
  for (auto& v : A) v = rng.uniform(-1.0, 1.0);
  gemm_abt(A.data(), lda, A.data(), lda, m, m, depth, C.data(), m, true);
  for (std::size_t j = 0; j < m; ++j) {
    for (std::size_t i = j; i < m; ++i) {
      double ref = 0.0;
      for (std::size_t k = 0; k < depth; ++k) ref += A[i + k * lda] * A[j + k * lda];
      EXPECT_NEAR(C[i + j * m], ref, kGemmTolerance);
    }
  }
}

// `count` doubles that end where an inaccessible page begins: a read or write past them faults.
// The sanitizer build compiles the kernel uninstrumented (CMakeLists.txt), so this is what holds
// its reads and writes to the buffers the header promises, in every build.
class GuardedBuffer {
 public:
  explicit GuardedBuffer(std::size_t count) {
    const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t data_pages = (count * sizeof(double) + page - 1) / page;
    size_ = (data_pages + 1) * page;
    void* p = mmap(nullptr, size_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::runtime_error("mmap failed");
    base_ = static_cast<char*>(p);
    if (mprotect(base_ + data_pages * page, page, PROT_NONE) != 0)
      throw std::runtime_error("mprotect failed");
    data_ = std::span<double>(reinterpret_cast<double*>(base_ + data_pages * page) - count, count);
  }
  ~GuardedBuffer() { munmap(base_, size_); }
  GuardedBuffer(const GuardedBuffer&) = delete;
  GuardedBuffer& operator=(const GuardedBuffer&) = delete;
  std::span<double> span() const { return data_; }

 private:
  char* base_ = nullptr;
  std::size_t size_ = 0;
  std::span<double> data_;
};

// A, B and C hold exactly what the header says is read or written (A's last column only its
// padded rows, B's and C's only their n and m rows), each against a guard page.
TEST(GemmAbt, StaysInsideTheDocumentedBuffers) {
  const std::size_t pad = gemm_abt_row_padding();
  Rng rng(3);
  for (std::size_t m : {1u, 6u, 17u}) {
    for (std::size_t n : {1u, 5u}) {
      for (std::size_t depth : {1u, 9u}) {
        for (bool lower : {false, true}) {
          if (lower && m != n) continue;
          const std::size_t rows = (m + pad - 1) / pad * pad, lda = rows;
          const std::size_t ldb = lower ? lda : n, ldc = m;
          GuardedBuffer A(lda * (depth - 1) + rows), C(ldc * (n - 1) + m);
          GuardedBuffer B(lower ? 1 : ldb * (depth - 1) + n);
          for (auto& v : A.span()) v = rng.uniform(-1.0, 1.0);
          for (auto& v : B.span()) v = rng.uniform(-1.0, 1.0);
          std::fill(C.span().begin(), C.span().end(), 0.0);
          const double* b = lower ? A.span().data() : B.span().data();
          gemm_abt(A.span().data(), lda, b, ldb, m, n, depth, C.span().data(), ldc, lower);
          for (std::size_t j = 0; j < n; ++j)
            for (std::size_t i = lower ? j : 0; i < m; ++i) {
              double ref = 0.0;
              for (std::size_t k = 0; k < depth; ++k) ref += A.span()[i + k * lda] * b[j + k * ldb];
              EXPECT_NEAR(C.span()[i + j * ldc], ref, kGemmTolerance)
                  << m << "x" << n << "x" << depth << (lower ? " lower" : "") << " at " << i << ","
                  << j;
            }
        }
      }
    }
  }
}

}  // namespace
}  // namespace skylight::nn::detail
