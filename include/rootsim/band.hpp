#pragma once
// Banded linear algebra for the rod's stiffness (docs/model.md, Newton solver): every element couples only to
// its neighbours, so the stiffness of the discrete rod, with node and element blocks interleaved, is a
// band matrix of half-bandwidth ~14. Storage is allocated by reserve() and reused: factorising and
// solving allocate nothing.
#include <Eigen/Core>
#include <memory>
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

// an entry of a band matrix outside its band
struct OffBandEntry {
  int row = 0, col = 0;
  double value = 0;
};

// a band matrix plus a few off-band entries (self-contact couples nodes far apart along the rod:
// docs/model.md, Newton solver), factorised as a sparse matrix: LU by KLU (SuiteSparse; threshold partial
// pivoting, AMD ordering) for the Newton step, and LDL^T of its symmetric part with AMD ordering (Eigen's
// SimplicialLDLT, no pivoting: the negative pivots count the negative eigenvalues, as BandLDLT's) for the
// stability check. The pattern holds the places where the band or the off-band entries held a nonzero
// since the size last changed (a quarter of the rod's band is structurally zero; factorising those zeros
// doubled KLU's work), so it changes with the size, the contacts, and the rare band entry that turns
// nonzero; each symbolic analysis is reused while it stays the same, and after the first LU of a
// relaxation, later ones keep its pivot sequence (KLU's refactorisation) unless a pivot became small. Unlike the band classes this allocates while assembling and factorising: it serves only
// the steps with self-contact. A copy starts empty.
// what SparseStiffness carries from one relaxation to the next (a checkpoint holds it, so that a resumed
// run factorises exactly as the uninterrupted one): the size and places of the pattern (band and
// off-band; the diagonal is always there), and the matrix whose full LU chose the pivots that later
// factorisations reuse (empty: none)
struct SparseMemory {
  int n = -1, kl = 0, ku = 0;      // n < 0: nothing
  std::vector<int> places;         // (column, row) pairs, sorted
  std::vector<double> pivotValues;  // the pattern's values, column by column
  // the matrix of the last factorisation when it was a refactorisation with those pivots (empty: the
  // last was the full one): restored too, so that a resumed run's first Newton step reuses the same
  // factors as the uninterrupted run's
  std::vector<double> lastValues;
  static constexpr auto fields() {
    using M = SparseMemory;
    return std::tuple{field("n", &M::n), field("kl", &M::kl), field("ku", &M::ku), field("places", &M::places),
                      field("pivotValues", &M::pivotValues), field("lastValues", &M::lastValues)};
  }
};

class SparseStiffness {
 public:
  SparseStiffness();
  ~SparseStiffness();
  SparseStiffness(const SparseStiffness&);
  SparseStiffness& operator=(const SparseStiffness&);
  // A = band (not yet factorised) + extra (entries at the same place are summed). The pattern keeps the
  // places of earlier calls (as zeros) until resetPattern() or a change of size, so that one symbolic
  // analysis serves a whole relaxation while contacts come and go.
  void assemble(const BandLU& band, const std::vector<OffBandEntry>& extra);
  void resetPattern();          // also: the next factorizeLU chooses its pivots anew
  // a relaxation of n unknowns begins: the pattern and the pivots of the last one serve it when it had
  // the same size (places only accumulate), else resetPattern
  void beginRelaxation(int n);
  SparseMemory memory() const;
  bool restore(const SparseMemory& mem);  // false (and reset) when mem is inconsistent
  int size() const;
  // the Newton step: A's LU (KLU)
  bool factorizeLU();          // false when singular
  void solveLU(double* b);     // after a successful factorizeLU (and until the next assemble, or
                               // across beginRelaxation of the same size: a chord step)
  bool hasFactors() const;     // factors to solve with
  bool factorizeSymmetric();   // LDL^T of (A + A^T) / 2; false when a pivot is zero or not finite
  int negativePivots(double relTol) const;  // as BandLDLT::negativePivots
  void solveSymmetric(double* b) const;
  long luAnalyses() const;     // symbolic analyses done so far (tests and benchmarks)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};
// a carry (fields.hpp) holds a SparseStiffness as its memory (a copy of one starts empty)
template <>
struct Carried<SparseStiffness> {
  using type = SparseMemory;
  static SparseMemory save(const SparseStiffness& s) { return s.memory(); }
  static bool restore(SparseStiffness& s, const SparseMemory& m) {
    if (s.restore(m)) return true;
    s.resetPattern();
    return false;
  }
};

}  // namespace rootsim
