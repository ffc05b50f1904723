// The sparse Jacobian of the Newton step with self-contact (sparse_stiffness.hpp): KLU for the step,
// Eigen's SimplicialLDLT for the stability check's inertia.
#include "rootsim/sparse_stiffness.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <klu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "rootsim/assert.hpp"

namespace rootsim {

struct SparseStiffness::Impl {
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  Matrix a, sym;
  std::vector<Eigen::Triplet<double, int>> triplets;
  Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  // KLU (SuiteSparse) for A itself: a symbolic analysis per pattern, a full factorisation (partial
  // pivoting) at the first Newton iteration of a relaxation, refactorisations with the same pivots after
  klu_common common{};
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  bool freshPivots = true;  // the next factorizeLU chooses its pivots anew (set by resetPattern)
  // the matrix of the last full factorisation (its pivots serve the refactorisations after it), and the
  // number of off-band places its pattern had: what a checkpoint needs to rebuild the same factors
  std::vector<double> pivotValues;
  size_t pivotPlaces = 0;
  std::vector<double> lastValues;  // the matrix of the last refactorisation (SparseMemory::lastValues)
  bool lastFull = true;             // the last factorisation was the full one
  int bandKl = 0, bandKu = 0;
  // the patterns the symbolic analyses were made for (column starts, row indices)
  std::vector<int> luOuter, luInner, symOuter, symInner;
  long luAnalyses = 0;
  bool symReady = false, luReady = false;
  // the places seen since resetPattern(), band and off-band, kept (as zeros when absent) so that the
  // pattern, and with it the symbolic analysis, stays the same over the iterations of one relaxation.
  // Band places only where the band held a nonzero: the rod's stiffness leaves about a quarter of its
  // band structurally zero (a node's row reaches two blocks each side, an element's three), and with
  // those zeros in the pattern KLU's refactorisation of a coil's Jacobian does about twice the flops
  std::vector<std::pair<int, int>> structural;  // (col, row), sorted
  int structuralSize = -1;

  Impl() { klu_defaults(&common); }
  ~Impl() { freeKlu(); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  void freeKlu() {
    if (numeric) klu_free_numeric(&numeric, &common);
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }

  // a's pattern: the diagonal and the places, each with its mirror (so the pattern is structurally
  // symmetric and the symmetric part (a + a^T) / 2 lives on it too), and what derives from it: the value
  // place of each band slot, and (deriveSymmetricPattern) the value place of each value's transpose and
  // sym's pattern
  std::vector<int> slot, transposed;  // slot: value place of band (i, j) at j * width + i - j + ku, or -1
  std::vector<int> extraIndex;        // the value places of the last assemble()'s off-band entries
  int bandWidth() const { return bandKl + bandKu + 1; }
  int slotOf(int i, int j) const { return slot[static_cast<size_t>(j) * bandWidth() + (i - j + bandKu)]; }

  void buildPattern(int n) {
    triplets.clear();
    for (int j = 0; j < n; ++j) triplets.emplace_back(j, j, 0.0);
    for (const auto& [col, row] : structural) {
      triplets.emplace_back(row, col, 0.0);
      triplets.emplace_back(col, row, 0.0);
    }
    a.resize(n, n);
    a.setFromTriplets(triplets.begin(), triplets.end());
    const int* outer = a.outerIndexPtr();
    const int* inner = a.innerIndexPtr();
    slot.assign(static_cast<size_t>(n) * bandWidth(), -1);
    for (int j = 0; j < n; ++j)
      for (int k = outer[j]; k < outer[j + 1]; ++k)
        if (inner[k] - j <= bandKl && j - inner[k] <= bandKu)
          slot[static_cast<size_t>(j) * bandWidth() + (inner[k] - j + bandKu)] = k;
    transposed.clear();  // derived when the symmetric part is first asked for (not every pattern is)
  }

  // transposed[] and sym's pattern, once per pattern
  void deriveSymmetricPattern() {
    if (!transposed.empty()) return;
    const int* outer = a.outerIndexPtr();
    const int* inner = a.innerIndexPtr();
    transposed.resize(static_cast<size_t>(a.nonZeros()));
    for (int j = 0; j < a.outerSize(); ++j)
      for (int k = outer[j]; k < outer[j + 1]; ++k)
        transposed[static_cast<size_t>(k)] =
            static_cast<int>(std::lower_bound(inner + outer[inner[k]], inner + outer[inner[k] + 1], j) - inner);
    sym = a;
  }

  // the value places of the off-band entries in the current pattern; false when it lacks one
  bool locate(const std::vector<OffBandEntry>& extra) {
    const int* outer = a.outerIndexPtr();
    const int* inner = a.innerIndexPtr();
    extraIndex.resize(extra.size());
    for (size_t e = 0; e < extra.size(); ++e) {
      const int* end = inner + outer[extra[e].col + 1];
      const int* k = std::lower_bound(inner + outer[extra[e].col], end, extra[e].row);
      if (k == end || *k != extra[e].row) return false;
      extraIndex[e] = static_cast<int>(k - inner);
    }
    return true;
  }

  // the band's nonzeros and the entries' places merged into the pattern, which is rebuilt (a new size
  // starts it afresh); each place is kept once, as (lower, higher) index (the pattern mirrors it)
  void mergePlaces(const BandLU& band, const std::vector<OffBandEntry>& extra) {
    const int n = band.size(), kl = band.kl(), ku = band.ku();
    const bool have = structuralSize == n && bandKl == kl && bandKu == ku && a.rows() == n;
    if (!have) {
      structural.clear();
      structuralSize = n;
    }
    // what the current pattern lacks is appended, then sorted and merged in once (one insertion at a
    // time was quadratic in the contact pairs: 10 % of a coiling run; a search of the sorted list for
    // each of the band's nonzeros was 5 %)
    const size_t known = structural.size();
    const int* outer = a.outerIndexPtr();
    const int* inner = a.innerIndexPtr();
    auto add = [&](int row, int col) { structural.emplace_back(std::min(row, col), std::max(row, col)); };
    for (int j = 0; j < n; ++j)
      for (int i = std::max(0, j - ku); i <= std::min(n - 1, j + kl); ++i)
        if (i != j && band.at(i, j) != 0.0 && !(have && slotOf(i, j) >= 0)) add(i, j);
    for (const OffBandEntry& e : extra) {
      ROOTSIM_ASSERT(e.row >= 0 && e.row < n && e.col >= 0 && e.col < n && (e.row - e.col > kl || e.col - e.row > ku),
                     "an off-band entry inside the matrix");
      if (have && std::binary_search(inner + outer[e.col], inner + outer[e.col + 1], e.row)) continue;
      add(e.row, e.col);
    }
    const auto mid = structural.begin() + static_cast<std::ptrdiff_t>(known);
    std::sort(mid, structural.end());
    structural.erase(std::unique(mid, structural.end()), structural.end());
    std::inplace_merge(structural.begin(), mid, structural.end());
    bandKl = kl;
    bandKu = ku;
    buildPattern(n);
  }

  // true (and the pattern remembered) when m's pattern differs from the one saved
  static bool patternChanged(const Matrix& m, std::vector<int>& outer, std::vector<int>& inner) {
    const int cols = static_cast<int>(m.outerSize());
    const int nnz = static_cast<int>(m.nonZeros());
    const bool same = static_cast<int>(outer.size()) == cols + 1 && static_cast<int>(inner.size()) == nnz &&
                      std::equal(outer.begin(), outer.end(), m.outerIndexPtr()) &&
                      std::equal(inner.begin(), inner.end(), m.innerIndexPtr());
    if (same) return false;
    outer.assign(m.outerIndexPtr(), m.outerIndexPtr() + cols + 1);
    inner.assign(m.innerIndexPtr(), m.innerIndexPtr() + nnz);
    return true;
  }
};

SparseStiffness::SparseStiffness() : impl_(std::make_unique<Impl>()) {}
SparseStiffness::~SparseStiffness() = default;
SparseStiffness::SparseStiffness(const SparseStiffness&) : impl_(std::make_unique<Impl>()) {}
SparseStiffness& SparseStiffness::operator=(const SparseStiffness& o) {
  if (this != &o) impl_ = std::make_unique<Impl>();
  return *this;
}

void SparseStiffness::assemble(const BandLU& band, const std::vector<OffBandEntry>& extra) {
  Impl& m = *impl_;
  const int n = band.size(), kl = band.kl(), ku = band.ku();
  const bool samePattern = m.structuralSize == n && m.a.rows() == n && m.bandKl == kl && m.bandKu == ku;
  // the band's values into their places; false when a nonzero has none in the current pattern
  auto fillBand = [&] {
    double* val = m.a.valuePtr();
    std::fill(val, val + m.a.nonZeros(), 0.0);
    const int width = m.bandWidth();
    for (int j = 0; j < n; ++j) {
      const int* slots = m.slot.data() + static_cast<size_t>(j) * width + ku - j;  // slots[i]: place of (i, j)
      for (int i = std::max(0, j - ku); i <= std::min(n - 1, j + kl); ++i) {
        const double v = band.at(i, j);
        if (slots[i] >= 0) val[slots[i]] = v;
        else if (v != 0.0) return false;
      }
    }
    return true;
  };
  if (!samePattern || !fillBand() || !m.locate(extra)) {
    m.mergePlaces(band, extra);
    const bool found = m.locate(extra);
    ROOTSIM_ASSERT(found, "every off-band entry has its place once merged in");
    (void)found;
    const bool placed = fillBand();
    ROOTSIM_ASSERT(placed, "every nonzero of the band has its place once merged in");
    (void)placed;
  }
  double* val = m.a.valuePtr();
  for (size_t e = 0; e < extra.size(); ++e) val[m.extraIndex[e]] += extra[e].value;
  m.symReady = m.luReady = false;
}

void SparseStiffness::resetPattern() {
  impl_->freshPivots = true;
  impl_->pivotValues.clear();
  impl_->structural.clear();
  impl_->structuralSize = -1;  // the next assemble() rebuilds the pattern
}

void SparseStiffness::beginRelaxation(int n) {
  if (impl_->structuralSize != n) resetPattern();
}

SparseMemory SparseStiffness::memory() const {
  const Impl& m = *impl_;
  SparseMemory mem;
  if (m.structuralSize < 0) return mem;
  mem.n = m.structuralSize;
  mem.kl = m.bandKl;
  mem.ku = m.bandKu;
  for (const auto& [col, row] : m.structural) {
    mem.places.push_back(col);
    mem.places.push_back(row);
  }
  if (!m.freshPivots && m.numeric && m.pivotPlaces == m.structural.size()) {
    mem.pivotValues = m.pivotValues;
    if (!m.lastFull) mem.lastValues = m.lastValues;
  }
  return mem;
}

bool SparseStiffness::restore(const SparseMemory& mem) {
  resetPattern();
  Impl& m = *impl_;
  if (mem.n < 0) return true;
  const int n = mem.n;
  if (n < 1 || mem.kl < 0 || mem.ku < 0 || mem.places.size() % 2 != 0) return false;
  m.structural.clear();
  for (size_t k = 0; k < mem.places.size(); k += 2) {
    const int col = mem.places[k], row = mem.places[k + 1];
    if (col < 0 || col >= n || row < 0 || row >= n) return false;
    if (!m.structural.empty() && !(m.structural.back() < std::pair<int, int>{col, row})) return false;  // sorted
    m.structural.emplace_back(col, row);
  }
  m.structuralSize = n;
  m.bandKl = mem.kl;
  m.bandKu = mem.ku;
  m.buildPattern(n);
  if (mem.pivotValues.empty()) return true;
  if (static_cast<long>(mem.pivotValues.size()) != static_cast<long>(m.a.nonZeros())) return false;
  // the factors the checkpointed run had: the same matrix through the same analysis and factorisation
  std::copy(mem.pivotValues.begin(), mem.pivotValues.end(), m.a.valuePtr());
  if (!factorizeLU()) return false;
  if (mem.lastValues.empty()) return true;
  // and the refactorisation that followed, with those pivots (it succeeded in the checkpointed run)
  if (mem.lastValues.size() != mem.pivotValues.size()) return false;
  std::copy(mem.lastValues.begin(), mem.lastValues.end(), m.a.valuePtr());
  if (!klu_refactor(m.a.outerIndexPtr(), m.a.innerIndexPtr(), m.a.valuePtr(), m.symbolic, m.numeric, &m.common))
    return false;
  m.lastValues = mem.lastValues;
  m.lastFull = false;
  return true;
}

bool SparseStiffness::hasFactors() const { return impl_->luReady && impl_->numeric != nullptr; }

int SparseStiffness::size() const { return static_cast<int>(impl_->a.rows()); }

bool SparseStiffness::factorizeLU() {
  Impl& m = *impl_;
  m.luReady = false;
  const int n = static_cast<int>(m.a.rows());
  int* ap = m.a.outerIndexPtr();
  int* ai = m.a.innerIndexPtr();
  double* ax = m.a.valuePtr();
  if (Impl::patternChanged(m.a, m.luOuter, m.luInner) || !m.symbolic) {
    m.freeKlu();
    m.symbolic = klu_analyze(n, ap, ai, &m.common);
    ++m.luAnalyses;
    if (!m.symbolic) return false;
    m.freshPivots = true;
  }
  if (!m.freshPivots && m.numeric) {
    // the pivot sequence of the last full factorisation (of this relaxation or an earlier one with the
    // same unknowns and places): no search, no allocation; a pivot that became small (rcond) calls for a
    // new search. (A check of KLU's pivot growth once per relaxation, which this did before, never came
    // near its threshold of 1e-8: its smallest value over 9 819 checks in 13 full-resolution coils was
    // 0.018, and it cost 4 % of their CPU. A poor pivot sequence would only make Newton steps inexact, which the
    // line search and the equilibrium criterion, on the exact residual, catch.)
    if (klu_refactor(ap, ai, ax, m.symbolic, m.numeric, &m.common) && klu_rcond(m.symbolic, m.numeric, &m.common) &&
        m.common.rcond > 1e-12) {
      m.luReady = true;
      m.lastValues.assign(ax, ax + m.a.nonZeros());
      m.lastFull = false;
      return true;
    }
  }
  if (m.numeric) klu_free_numeric(&m.numeric, &m.common);
  m.numeric = klu_factor(ap, ai, ax, m.symbolic, &m.common);
  if (!m.numeric || m.common.status != KLU_OK) return false;
  m.pivotValues.assign(ax, ax + m.a.nonZeros());
  m.pivotPlaces = m.structural.size();
  m.freshPivots = false;
  m.luReady = true;
  m.lastFull = true;
  return true;
}

void SparseStiffness::solveLU(double* b) {
  Impl& m = *impl_;
  ROOTSIM_ASSERT(m.luReady, "solveLU after a successful factorizeLU");
  klu_solve(m.symbolic, m.numeric, size(), 1, b, &m.common);
}

bool SparseStiffness::factorizeSymmetric() {
  Impl& m = *impl_;
  if (m.symReady) return true;
  m.deriveSymmetricPattern();
  const double* av = m.a.valuePtr();
  double* sv = m.sym.valuePtr();
  for (Eigen::Index k = 0; k < m.a.nonZeros(); ++k) sv[k] = 0.5 * (av[m.transposed[static_cast<size_t>(k)]] + av[k]);
  if (Impl::patternChanged(m.sym, m.symOuter, m.symInner)) m.ldlt.analyzePattern(m.sym);
  m.ldlt.factorize(m.sym);
  if (m.ldlt.info() != Eigen::Success) return false;
  const auto& d = m.ldlt.vectorD();
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (d[i] == 0.0 || !std::isfinite(d[i])) return false;
  m.symReady = true;
  return true;
}

int SparseStiffness::negativePivots(double relTol) const {
  const auto& d = impl_->ldlt.vectorD();
  const double big = d.cwiseAbs().maxCoeff();
  int neg = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) neg += d[i] < -relTol * big;
  return neg;
}

void SparseStiffness::solveSymmetric(double* b) const {
  Eigen::Map<Eigen::VectorXd> x(b, size());
  x = impl_->ldlt.solve(x).eval();
}

long SparseStiffness::luAnalyses() const { return impl_->luAnalyses; }

}  // namespace rootsim
