#include "rootsim/response_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

namespace rootsim {

int quadraticTerms(int n) { return 1 + n + n * (n + 1) / 2; }

Eigen::VectorXd quadraticBasis(const Eigen::VectorXd& u) {
  const int n = static_cast<int>(u.size());
  Eigen::VectorXd b(quadraticTerms(n));
  int k = 0;
  b(k++) = 1.0;
  for (int i = 0; i < n; ++i) b(k++) = u(i);
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) b(k++) = u(i) * u(j);
  return b;
}

Eigen::VectorXd ResponseSurface::value(const Eigen::VectorXd& u) const {
  return coef.transpose() * quadraticBasis((u - centre) / scale);
}

Eigen::MatrixXd ResponseSurface::jacobian(const Eigen::VectorXd& u) const {
  const int n = static_cast<int>(u.size());
  const Eigen::VectorXd v = (u - centre) / scale;
  // d basis / d v, terms x n
  Eigen::MatrixXd db = Eigen::MatrixXd::Zero(quadraticTerms(n), n);
  int k = 1;
  for (int i = 0; i < n; ++i) db(k++, i) = 1.0;
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j, ++k) {
      db(k, i) += v(j);
      db(k, j) += v(i);
    }
  return coef.transpose() * db / scale;
}

ResponseSurface fitResponseSurface(const std::vector<Eigen::VectorXd>& u, const std::vector<Eigen::VectorXd>& y,
                                   const Eigen::VectorXd& centre, double scale) {
  if (u.empty() || u.size() != y.size()) throw std::invalid_argument("fitResponseSurface: points and values differ");
  const int n = static_cast<int>(centre.size()), terms = quadraticTerms(n), N = static_cast<int>(u.size());
  if (N <= terms) throw std::invalid_argument("fitResponseSurface: needs more points than terms");
  const int m = static_cast<int>(y.front().size());
  Eigen::MatrixXd A(N, terms), Y(N, m);
  for (int k = 0; k < N; ++k) {
    A.row(k) = quadraticBasis((u[static_cast<std::size_t>(k)] - centre) / scale).transpose();
    Y.row(k) = y[static_cast<std::size_t>(k)].transpose();
  }
  ResponseSurface s;
  s.centre = centre;
  s.scale = scale;
  s.points = N;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  s.coef = qr.solve(Y);
  const Eigen::MatrixXd r = A * s.coef - Y;
  s.noiseCov = r.transpose() * r / static_cast<double>(N - terms);
  return s;
}

Eigen::MatrixXd totalCovariance(const ResponseSurface& s, const Eigen::MatrixXd& traceCov) {
  return s.noiseCov + traceCov;
}

double chiSquareOf(const Eigen::VectorXd& y, const Eigen::VectorXd& measured, const Eigen::MatrixXd& C) {
  const Eigen::VectorXd d = y - measured;
  return d.dot(C.ldlt().solve(d));
}

double surfaceChiSquare(const ResponseSurface& s, const Eigen::VectorXd& u, const Eigen::VectorXd& measured,
                        const Eigen::MatrixXd& traceCov) {
  return chiSquareOf(s.value(u), measured, totalCovariance(s, traceCov));
}

FitUncertainty uncertaintyAt(const ResponseSurface& s, const Eigen::VectorXd& u, const Eigen::VectorXd& measured,
                             const Eigen::MatrixXd& traceCov) {
  const int n = static_cast<int>(u.size());
  FitUncertainty f;
  const Eigen::MatrixXd J = s.jacobian(u);
  f.fisher = J.transpose() * totalCovariance(s, traceCov).ldlt().solve(J);
  f.chi2 = surfaceChiSquare(s, u, measured, traceCov);
  f.dof = static_cast<int>(J.rows()) - n;
  f.scale = f.dof > 0 ? std::max(1.0, f.chi2 / f.dof) : 1.0;
  f.sigma.assign(static_cast<std::size_t>(n), std::numeric_limits<double>::quiet_NaN());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(f.fisher);
  double top = eig.eigenvalues().cwiseAbs().maxCoeff();
  for (int e = 0; e < n; ++e)
    // chi2 rises by lambda d^2 over a distance d along the eigenvector: flat when below 1 at d = 1/2
    if (eig.eigenvalues()(e) * 0.25 < 1.0) f.flat.push_back(eig.eigenvectors().col(e));
  if (eig.eigenvalues().minCoeff() > 1e-12 * std::max(top, 1e-300)) {
    f.covariance = f.fisher.inverse() * f.scale;
    for (int i = 0; i < n; ++i) {
      bool alongFlat = false;
      for (const Eigen::VectorXd& v : f.flat) alongFlat = alongFlat || std::abs(v(i)) > 0.1;
      if (!alongFlat) f.sigma[static_cast<std::size_t>(i)] = std::sqrt(f.covariance(i, i));
    }
  }
  return f;
}

}  // namespace rootsim
