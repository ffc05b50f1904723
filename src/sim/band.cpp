// The band LU and LDL^T factorisations of the rod's stiffness (band.hpp).
#include "rootsim/band.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "rootsim/assert.hpp"

namespace rootsim {

void BandLU::reset(int n, int kl, int ku) {
  ROOTSIM_ASSERT(n >= 1 && kl >= 0 && ku >= 0, "a band matrix of positive size");
  n_ = n;
  kl_ = kl;
  ku_ = ku;
  kv_ = kl + ku;
  ld_ = 2 * kl + ku + 1;
  ab_.assign(static_cast<size_t>(ld_) * static_cast<size_t>(n), 0.0);  // reuses the capacity
  piv_.assign(static_cast<size_t>(n), 0);
  lastL_.assign(static_cast<size_t>(n), 0);
  firstU_.assign(static_cast<size_t>(n), 0);
  colLast_.resize(static_cast<size_t>(n));
  rowLast_.resize(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) colLast_[static_cast<size_t>(j)] = rowLast_[static_cast<size_t>(j)] = j;
}

void BandLU::addDiagonalBlock(int o, const BandLU& b, int k) {
  ROOTSIM_ASSERT(o >= 0 && o + b.n_ <= n_ && k <= b.kl_ && k <= b.ku_ && k <= kl_ && k <= ku_, "a block inside the band");
  for (int j = 0; j < b.n_; ++j) {
    const int i0 = std::max(0, j - k), i1 = std::min(b.n_ - 1, j + k);
    const double* src = b.ab_.data() + static_cast<size_t>(b.kv_ - j + j * b.ld_);  // src[i] = B(i, j)
    double* dst = ab_.data() + static_cast<size_t>(kv_ - j + (o + j) * ld_);     // dst[i] = A(o + i, o + j)
    int& colLast = colLast_[static_cast<size_t>(o + j)];
    for (int i = i0; i <= i1; ++i) {
      const double v = src[i];
      if (v == 0.0) continue;
      dst[i] += v;
      colLast = std::max(colLast, o + i);
      int& rowLast = rowLast_[static_cast<size_t>(o + i)];
      rowLast = std::max(rowLast, o + j);
    }
  }
}

void BandLU::scanProfile() {
  for (int j = 0; j < n_; ++j) {
    const double* col = ab_.data() + static_cast<size_t>(j) * ld_ + kv_;  // col[i] = L(j + i, j)
    int last = 0;
    for (int i = 1; i <= std::min(kl_, n_ - 1 - j); ++i)
      if (col[i] != 0.0) last = i;
    lastL_[static_cast<size_t>(j)] = last;
    const double* u = ab_.data() + static_cast<size_t>(j) * ld_ + kv_ - j;  // u[i] = U(i, j)
    int first = j;
    for (int i = std::max(0, j - kv_); i < j; ++i)
      if (u[i] != 0.0) { first = i; break; }
    firstU_[static_cast<size_t>(j)] = first;
  }
}

bool BandLU::factorize() {
  // column j: pick the largest of A(j..j+km, j) as pivot, swap its row up across the columns the
  // interchanges can reach (ju), scale the multipliers, update the trailing band
  // Only the structure add() built is visited (colLast_, rowLast_, grown by the fill of each step):
  // the skipped entries are exact zeros, so the factors are those of the full band algorithm; the
  // Newton solver's frozen twists, a tridiagonal chain inside the band, then cost a few operations
  // per row instead of a full band's.
  double* ab = ab_.data();
  const int ld = ld_, kv = kv_;
  int* colLast = colLast_.data();
  int* rowLast = rowLast_.data();
  int ju = 0;
  for (int j = 0; j < n_; ++j) firstU_[static_cast<size_t>(j)] = j;
  for (int j = 0; j < n_; ++j) {
    const int km = std::min({kl_, n_ - 1 - j, colLast[j] - j});  // rows below j that may be nonzero
    double* col = ab + static_cast<size_t>(j) * ld + kv;  // col[i] = A(j + i, j)
    int jp = 0;
    double best = std::abs(col[0]);
    for (int i = 1; i <= km; ++i)
      if (std::abs(col[i]) > best) { best = std::abs(col[i]); jp = i; }
    piv_[static_cast<size_t>(j)] = j + jp;
    if (!(best > 0.0) || !std::isfinite(best)) return false;
    ju = std::max(ju, std::min(j + ku_ + jp, n_ - 1));
    if (jp != 0) {
      for (int c = j; c <= ju; ++c) {
        std::swap(ab[kv + j - c + static_cast<size_t>(c) * ld], ab[kv + j + jp - c + static_cast<size_t>(c) * ld]);
        colLast[c] = std::max(colLast[c], j + jp);
      }
      std::swap(rowLast[j], rowLast[j + jp]);
    }
    int last = 0;
    if (km > 0) {
      const double inv = 1.0 / col[0];
      for (int i = 1; i <= km; ++i) {
        col[i] *= inv;
        if (col[i] != 0.0) last = i;
      }
    }
    lastL_[static_cast<size_t>(j)] = last;
    // row j of U is final now: its nonzeros set the first rows of U's columns (the update below
    // skips a zero multiplier or a zero U(j, c): exact zeros, the same result as the full loop)
    const int cEnd = std::min(ju, rowLast[j]);  // pivot row j's last possibly nonzero column
    for (int c = j + 1; c <= cEnd; ++c) {
      double* cc = ab + static_cast<size_t>(c) * ld + kv + j - c;  // cc[i] = A(j + i, c)
      const double u = cc[0];
      if (u == 0.0) continue;
      if (firstU_[static_cast<size_t>(c)] > j) firstU_[static_cast<size_t>(c)] = j;
      for (int i = 1; i <= last; ++i) cc[i] -= col[i] * u;
      colLast[c] = std::max(colLast[c], j + last);
    }
    // the rows that took a multiple of row j now reach as far as it does
    if (cEnd > j)
      for (int i = 1; i <= last; ++i)
        if (col[i] != 0.0) rowLast[j + i] = std::max(rowLast[j + i], cEnd);
  }
  return true;
}

void BandLU::solve(double* b) const {
  const double* ab = ab_.data();
  const int ld = ld_, kv = kv_;
  // L y = P b
  for (int j = 0; j + 1 < n_; ++j) {
    const int km = std::min(kl_, n_ - 1 - j);
    const int l = piv_[static_cast<size_t>(j)];
    if (l != j) std::swap(b[l], b[j]);
    const double* col = ab + static_cast<size_t>(j) * ld + kv;
    for (int i = 1; i <= std::min(km, lastL_[static_cast<size_t>(j)]); ++i) b[j + i] -= col[i] * b[j];
  }
  // U x = y (U has kl + ku super-diagonals after the interchanges)
  for (int j = n_ - 1; j >= 0; --j) {
    const double* col = ab + static_cast<size_t>(j) * ld + kv - j;  // col[i] = A(i, j)
    b[j] /= col[j];
    const double bj = b[j];
    for (int i = std::max(firstU_[static_cast<size_t>(j)], j - kv); i < j; ++i) b[i] -= col[i] * bj;
  }
}

void BandLDLT::reset(int n, int k) {
  ROOTSIM_ASSERT(n >= 1 && k >= 0 && k < 64, "a symmetric band matrix of positive size, half-bandwidth < 64");
  n_ = n;
  k_ = k;
  a_.assign(static_cast<size_t>(k + 1) * static_cast<size_t>(n), 0.0);
  first_.assign(static_cast<size_t>(n), 0);
  last_.assign(static_cast<size_t>(n), 0);
}

bool BandLDLT::factorize() {
  // column by column: D_j = A_jj - sum_m L_jm^2 D_m, L_ij = (A_ij - sum_m L_im L_jm D_m) / D_j, the sums
  // over the columns m inside both rows' envelopes (L_im = 0 before row i's first nonzero: the
  // factorisation fills only inside the envelope, so the skipped terms are exact zeros)
  const int K = k_ + 1;
  double* a = a_.data();
  int* first = first_.data();
  int* last = last_.data();
  for (int i = 0; i < n_; ++i) {
    int f = i;
    for (int m = std::max(0, i - k_); m < i; ++m)
      if (a[(i - m) + static_cast<size_t>(m) * K] != 0.0) { f = m; break; }
    first[i] = f;
    last[i] = i;
  }
  for (int i = 0; i < n_; ++i)
    for (int m = first[i]; m < i; ++m) last[m] = std::max(last[m], i);
  double w[64];  // w[m - j0] = L_jm D_m for the columns m in [j0, j) that reach row j
  for (int j = 0; j < n_; ++j) {
    const int j0 = first[j];
    double d = a[static_cast<size_t>(j) * K];
    for (int m = j0; m < j; ++m) {
      const double l = a[(j - m) + static_cast<size_t>(m) * K];
      w[m - j0] = l * a[static_cast<size_t>(m) * K];
      d -= l * w[m - j0];
    }
    if (!(std::abs(d) > 0.0) || !std::isfinite(d)) return false;
    a[static_cast<size_t>(j) * K] = d;
    for (int i = j + 1; i <= last[j]; ++i) {
      if (first[i] > j) continue;  // L_ij = 0: outside row i's envelope
      double s = a[(i - j) + static_cast<size_t>(j) * K];
      for (int m = std::max(j0, first[i]); m < j; ++m) s -= a[(i - m) + static_cast<size_t>(m) * K] * w[m - j0];
      a[(i - j) + static_cast<size_t>(j) * K] = s / d;
    }
  }
  return true;
}

int BandLDLT::negativePivots(double relTol) const {
  double big = 0.0;
  for (int j = 0; j < n_; ++j) big = std::max(big, std::abs(a_[static_cast<size_t>(j) * (k_ + 1)]));
  int neg = 0;
  for (int j = 0; j < n_; ++j) neg += a_[static_cast<size_t>(j) * (k_ + 1)] < -relTol * big;
  return neg;
}

void BandLDLT::solve(double* b) const {
  const int K = k_ + 1;
  const double* a = a_.data();
  // inside the envelope only (outside it L is zero)
  for (int j = 0; j < n_; ++j) {
    const int iMax = last_[static_cast<size_t>(j)];
    for (int i = j + 1; i <= iMax; ++i) b[i] -= a[(i - j) + static_cast<size_t>(j) * K] * b[j];
  }
  for (int j = 0; j < n_; ++j) b[j] /= a[static_cast<size_t>(j) * K];
  for (int j = n_ - 1; j >= 0; --j) {
    const int iMax = last_[static_cast<size_t>(j)];
    for (int i = j + 1; i <= iMax; ++i) b[j] -= a[(i - j) + static_cast<size_t>(j) * K] * b[i];
  }
}

bool BandLU::restore(int n, int kl, int ku, const std::vector<double>& ab, const std::vector<int>& piv) {
  if (n < 1 || kl < 0 || ku < 0) return false;
  const size_t ld = static_cast<size_t>(2 * kl + ku + 1);
  if (ab.size() != ld * static_cast<size_t>(n) || piv.size() != static_cast<size_t>(n)) return false;
  for (int p : piv)
    if (p < 0 || p >= n) return false;
  reset(n, kl, ku);
  std::copy(ab.begin(), ab.end(), ab_.begin());
  std::copy(piv.begin(), piv.end(), piv_.begin());
  scanProfile();
  return true;
}

}  // namespace rootsim
