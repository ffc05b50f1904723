#pragma once
// The Newton step's Jacobian as a sparse matrix (docs/model.md, Newton solver): the band of the rod's
// stiffness plus the off-band couplings self-contact makes, factorised by KLU (SuiteSparse) and Eigen's
// SimplicialLDLT. Used instead of the band factorisations while a self-contact couples nodes far apart.
#include <memory>
#include <vector>

#include "rootsim/band.hpp"
#include "rootsim/fields.hpp"

namespace rootsim {

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
// relaxation, later ones keep its pivot sequence (KLU's refactorisation) unless a pivot became small. The
// pattern's arrays are kept from pattern to pattern and grow only past their largest size (high_water.hpp);
// KLU allocates its own analysis when the pattern changes and its factors at a full factorisation. A copy
// starts empty.
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
