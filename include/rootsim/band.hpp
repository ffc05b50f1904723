#pragma once
// Banded linear algebra for the rod's stiffness (docs/model.md, Newton solver): every element couples only to
// its neighbours, so the stiffness of the discrete rod, with node and element blocks interleaved, is a
// band matrix of half-bandwidth ~14. Storage is allocated by reserve() and reused: factorising and
// solving allocate nothing.
#include <Eigen/Core>
#include <vector>

#include "rootsim/fields.hpp"

namespace rootsim {

// general band matrix with kl sub- and ku super-diagonals and its LU factorisation with partial
// pivoting (the LAPACK dgbtf2/dgbtrs algorithm, written out; LAPACK's band storage with kl extra rows
// for the fill-in of row interchanges)
class BandLU {
 public:
  // sizes the storage for n unknowns; allocates only when n grows past what was reserved
  void reset(int n, int kl, int ku);
  int size() const { return n_; }
  int kl() const { return kl_; }
  int ku() const { return ku_; }
  // A(i, j) += v; only inside the band (|i - j| within kl, ku)
  void add(int i, int j, double v) {
    ab_[static_cast<size_t>(kv_ + i - j + j * ld_)] += v;
    if (i > colLast_[static_cast<size_t>(j)]) colLast_[static_cast<size_t>(j)] = i;
    if (j > rowLast_[static_cast<size_t>(i)]) rowLast_[static_cast<size_t>(i)] = j;
  }
  // A(i0 + r, j0 + c) += s * k(r, c) for a 3 x 3 block inside the band (its zeros join the structure:
  // the factors are the same, as factorize() then only multiplies by them)
  template <class Block>
  void addBlock(int i0, int j0, double s, const Block& k) {
    for (int c = 0; c < 3; ++c) {
      double* col = ab_.data() + static_cast<size_t>(kv_ + i0 - (j0 + c) + (j0 + c) * ld_);
      for (int r = 0; r < 3; ++r) col[r] += s * k(r, c);
      int& last = colLast_[static_cast<size_t>(j0 + c)];
      if (i0 + 2 > last) last = i0 + 2;
    }
    for (int r = 0; r < 3; ++r) {
      int& last = rowLast_[static_cast<size_t>(i0 + r)];
      if (j0 + 2 > last) last = j0 + 2;
    }
  }
  double at(int i, int j) const { return ab_[static_cast<size_t>(kv_ + i - j + j * ld_)]; }
  // A(o + i, o + j) += B(i, j) for B's nonzeros within half-bandwidth k of its diagonal (B unfactorised,
  // k at most B's and this matrix's bands): a block of a larger system, as add() would place each
  void addDiagonalBlock(int o, const BandLU& b, int k);
  bool inBand(int i, int j) const { return i - j <= kl_ && j - i <= ku_; }
  // factorises in place; false when a pivot is exactly zero (singular)
  bool factorize();
  // solves A x = b in place (after factorize())
  void solve(double* b) const;
  // the raw storage (band and its LU factors, pivots), to carry factors across a checkpoint
  const std::vector<double>& storage() const { return ab_; }
  const std::vector<int>& pivots() const { return piv_; }
  // restores what storage() and pivots() of a matrix of these sizes held; false when they do not fit
  bool restore(int n, int kl, int ku, const std::vector<double>& ab, const std::vector<int>& piv);

 private:
  void scanProfile();
  int n_ = 0, kl_ = 0, ku_ = 0, kv_ = 0, ld_ = 1;
  std::vector<double> ab_;
  std::vector<int> piv_;
  // the factors' profile, so that a solve skips their structural zeros (the Newton solver's frozen
  // twists form a tridiagonal chain inside the band): the last nonzero multiplier of column j (offset
  // below the diagonal) and the first nonzero row of U's column j
  std::vector<int> lastL_, firstU_;
  // the structure add() built (and the fill the factorisation adds to it): the last row of column j
  // and the last column of row i that may be nonzero; factorize() skips what lies beyond
  std::vector<int> colLast_, rowLast_;
};

// symmetric band matrix (half-bandwidth k, lower band stored) and its LDL^T factorisation without
// pivoting: the count of negative pivots is the number of negative eigenvalues (Sylvester's law of
// inertia) whenever the factorisation exists
class BandLDLT {
 public:
  void reset(int n, int k);
  int size() const { return n_; }
  // A(i, j) = A(j, i) += v for i >= j within the band
  void addLower(int i, int j, double v) { a_[static_cast<size_t>((i - j) + j * (k_ + 1))] += v; }
  // false when a pivot is zero or not finite
  bool factorize();
  int negativePivots(double relTol) const;
  void solve(double* b) const;

 private:
  int n_ = 0, k_ = 0;
  std::vector<double> a_;  // column j holds A(j..j+k, j); after factorize(): D on the diagonal, L below
  // the envelope: row i's first nonzero column (the factorisation fills nothing before it), and the
  // last row whose envelope reaches column j; factorisation and solves skip what lies outside
  std::vector<int> first_, last_;
};

}  // namespace rootsim
