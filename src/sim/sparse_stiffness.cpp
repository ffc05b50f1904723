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
#include "rootsim/high_water.hpp"

namespace rootsim {

struct SparseStiffness::Impl {
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  // A in compressed columns (column starts, row indices, values) in storage kept from pattern to pattern
  // (an Eigen matrix reallocates whenever its pattern is rebuilt); sym, A's symmetric part, only for the
  // stability check
  int n = 0;
  std::vector<int> ap, ai;
  std::vector<double> ax;
  Matrix sym;
  int nnz() const { return n > 0 ? ap[static_cast<size_t>(n)] : 0; }
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
  std::vector<std::pair<int, int>> merged;      // scratch of mergePlaces (swapped with structural)
  int structuralSize = -1;

  Impl() {
    klu_defaults(&common);
    common.scale = kFullScale;
  }
  ~Impl() { freeKlu(); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  // A's values refactorised on the pivot sequence of the last full factorisation, without row scaling:
  // the scaling serves the full factorisation's choice of pivots (klu_factor scales, KLU's default); with
  // the pivots fixed it changes only the rounding and is one more pass over the matrix (KLU then solves
  // unscaled too: klu_refactor drops the factors' scale factors)
  bool refactor() {
    common.scale = -1;
    const bool ok = klu_refactor(ap.data(), ai.data(), ax.data(), symbolic, numeric, &common) != 0;
    common.scale = kFullScale;
    return ok;
  }
  static constexpr int kFullScale = 2;  // KLU's default row scaling (by each row's largest entry)
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

  void buildPattern(int size) {
    // each column: its diagonal and the rows of the places in it, both ways (a place (p, q), p < q, is
    // row q of column p and row p of column q), sorted
    n = size;
    resizeHighWater(ap, static_cast<size_t>(n) + 1);
    std::fill(ap.begin(), ap.end(), 0);
    for (int j = 0; j < n; ++j) ++ap[static_cast<size_t>(j) + 1];
    for (const auto& [p, q] : structural) {
      ++ap[static_cast<size_t>(p) + 1];
      ++ap[static_cast<size_t>(q) + 1];
    }
    for (int j = 0; j < n; ++j) ap[static_cast<size_t>(j) + 1] += ap[static_cast<size_t>(j)];
    resizeHighWater(ai, static_cast<size_t>(nnz()));
    resizeHighWater(ax, static_cast<size_t>(nnz()));
    std::fill(ax.begin(), ax.end(), 0.0);
    resizeHighWater(slot, static_cast<size_t>(n));  // slot as each column's fill count for now
    std::copy(ap.begin(), ap.begin() + n, slot.begin());
    auto put = [&](int row, int col) { ai[static_cast<size_t>(slot[static_cast<size_t>(col)]++)] = row; };
    for (int j = 0; j < n; ++j) put(j, j);
    for (const auto& [p, q] : structural) {
      put(q, p);
      put(p, q);
    }
    for (int j = 0; j < n; ++j) std::sort(ai.begin() + ap[static_cast<size_t>(j)], ai.begin() + ap[static_cast<size_t>(j) + 1]);
    const int* outer = ap.data();
    const int* inner = ai.data();
    resizeHighWater(slot, static_cast<size_t>(n) * bandWidth());
    std::fill(slot.begin(), slot.end(), -1);
    for (int j = 0; j < n; ++j)
      for (int k = outer[j]; k < outer[j + 1]; ++k)
        if (inner[k] - j <= bandKl && j - inner[k] <= bandKu)
          slot[static_cast<size_t>(j) * bandWidth() + (inner[k] - j + bandKu)] = k;
    transposed.clear();  // derived when the symmetric part is first asked for (not every pattern is)
  }

  // transposed[] and sym's pattern, once per pattern
  void deriveSymmetricPattern() {
    if (!transposed.empty()) return;
    const int* outer = ap.data();
    const int* inner = ai.data();
    resizeHighWater(transposed, static_cast<size_t>(nnz()));
    for (int j = 0; j < n; ++j)
      for (int k = outer[j]; k < outer[j + 1]; ++k)
        transposed[static_cast<size_t>(k)] =
            static_cast<int>(std::lower_bound(inner + outer[inner[k]], inner + outer[inner[k] + 1], j) - inner);
    sym = Eigen::Map<const Matrix>(n, n, nnz(), ap.data(), ai.data(), ax.data());
  }

  // the value places of the off-band entries in the current pattern; false when it lacks one
  bool locate(const std::vector<OffBandEntry>& extra) {
    const int* outer = ap.data();
    const int* inner = ai.data();
    resizeHighWater(extraIndex, extra.size());
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
    const int size = band.size(), kl = band.kl(), ku = band.ku();
    const bool have = structuralSize == size && bandKl == kl && bandKu == ku && n == size;
    if (!have) {
      structural.clear();
      structuralSize = size;
    }
    // what the current pattern lacks is appended, then sorted and merged in once (one insertion at a
    // time was quadratic in the contact pairs: 10 % of a coiling run; a search of the sorted list for
    // each of the band's nonzeros was 5 %)
    const size_t known = structural.size();
    const int* outer = ap.data();
    const int* inner = ai.data();
    auto add = [&](int row, int col) { structural.emplace_back(std::min(row, col), std::max(row, col)); };
    for (int j = 0; j < size; ++j)
      for (int i = std::max(0, j - ku); i <= std::min(size - 1, j + kl); ++i)
        if (i != j && band.at(i, j) != 0.0 && !(have && slotOf(i, j) >= 0)) add(i, j);
    for (const OffBandEntry& e : extra) {
      ROOTSIM_ASSERT(e.row >= 0 && e.row < size && e.col >= 0 && e.col < size && (e.row - e.col > kl || e.col - e.row > ku),
                     "an off-band entry inside the matrix");
      if (have && std::binary_search(inner + outer[e.col], inner + outer[e.col + 1], e.row)) continue;
      add(e.row, e.col);
    }
    const auto mid = structural.begin() + static_cast<std::ptrdiff_t>(known);
    std::sort(mid, structural.end());
    structural.erase(std::unique(mid, structural.end()), structural.end());
    // merged in scratch kept from call to call (std::inplace_merge takes a buffer of its own each time)
    resizeHighWater(merged, structural.size());
    std::merge(structural.begin(), mid, mid, structural.end(), merged.begin());
    structural.swap(merged);
    bandKl = kl;
    bandKu = ku;
    buildPattern(size);
  }

  // true (and the pattern remembered) when m's pattern differs from the one saved
  static bool patternChanged(int cols, const int* mOuter, const int* mInner, std::vector<int>& outer,
                             std::vector<int>& inner) {
    const int nnz = mOuter[cols];
    const bool same = static_cast<int>(outer.size()) == cols + 1 && static_cast<int>(inner.size()) == nnz &&
                      std::equal(outer.begin(), outer.end(), mOuter) && std::equal(inner.begin(), inner.end(), mInner);
    if (same) return false;
    assignHighWater(outer, mOuter, mOuter + cols + 1);
    assignHighWater(inner, mInner, mInner + nnz);
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
  const bool samePattern = m.structuralSize == n && m.n == n && m.bandKl == kl && m.bandKu == ku;
  // the band's values into their places; false when a nonzero has none in the current pattern
  auto fillBand = [&] {
    double* val = m.ax.data();
    std::fill(val, val + m.nnz(), 0.0);
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
  double* val = m.ax.data();
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
  if (static_cast<long>(mem.pivotValues.size()) != static_cast<long>(m.nnz())) return false;
  // the factors the checkpointed run had: the same matrix through the same analysis and factorisation
  std::copy(mem.pivotValues.begin(), mem.pivotValues.end(), m.ax.data());
  if (!factorizeLU()) return false;
  if (mem.lastValues.empty()) return true;
  // and the refactorisation that followed, with those pivots (it succeeded in the checkpointed run)
  if (mem.lastValues.size() != mem.pivotValues.size()) return false;
  std::copy(mem.lastValues.begin(), mem.lastValues.end(), m.ax.data());
  if (!m.refactor()) return false;
  m.lastValues = mem.lastValues;
  m.lastFull = false;
  return true;
}

bool SparseStiffness::hasFactors() const { return impl_->luReady && impl_->numeric != nullptr; }

int SparseStiffness::size() const { return impl_->n; }

bool SparseStiffness::factorizeLU() {
  Impl& m = *impl_;
  m.luReady = false;
  const int n = m.n;
  int* ap = m.ap.data();
  int* ai = m.ai.data();
  double* ax = m.ax.data();
  if (Impl::patternChanged(n, ap, ai, m.luOuter, m.luInner) || !m.symbolic) {
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
    if (m.refactor() && klu_rcond(m.symbolic, m.numeric, &m.common) &&
        m.common.rcond > 1e-12) {
      m.luReady = true;
      assignHighWater(m.lastValues, ax, ax + m.nnz());
      m.lastFull = false;
      return true;
    }
  }
  if (m.numeric) klu_free_numeric(&m.numeric, &m.common);
  m.numeric = klu_factor(ap, ai, ax, m.symbolic, &m.common);
  if (!m.numeric || m.common.status != KLU_OK) return false;
  assignHighWater(m.pivotValues, ax, ax + m.nnz());
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
  const double* av = m.ax.data();
  double* sv = m.sym.valuePtr();
  for (int k = 0; k < m.nnz(); ++k) sv[k] = 0.5 * (av[m.transposed[static_cast<size_t>(k)]] + av[k]);
  if (Impl::patternChanged(m.n, m.sym.outerIndexPtr(), m.sym.innerIndexPtr(), m.symOuter, m.symInner))
    m.ldlt.analyzePattern(m.sym);
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
