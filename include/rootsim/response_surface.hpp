#pragma once
// A quadratic response surface of a simulator's outputs over its parameters (docs/experiments.md, "Fit").
// A root's shape is a deterministic but sensitive function of its parameters: the skew of a skewing root
// jumps by a degree or two between parameters 1 % apart (docs/experiments.md measures it), so a fit that
// chases single runs chases that scatter. The surface is the smooth trend of every output over a trust
// region, fitted by least squares to the runs in it; what the runs scatter about it is the model's own
// noise, which the fit adds to the trace's uncertainty. Plain linear algebra: no file formats here.
#include <vector>

#include <Eigen/Core>

namespace rootsim {

// the number of terms of a full quadratic in n variables: 1 + n + n (n + 1) / 2
int quadraticTerms(int n);
// the terms at u: 1, u_1 .. u_n, then u_i u_j for i <= j (row-major)
Eigen::VectorXd quadraticBasis(const Eigen::VectorXd& u);

struct ResponseSurface {
  Eigen::VectorXd centre;     // the basis is taken of (u - centre) / scale: conditioned in a small region
  double scale = 1;
  Eigen::MatrixXd coef;       // terms x outputs
  Eigen::MatrixXd noiseCov;   // the runs' scatter about the surface: the residuals' covariance between
                              // outputs, R'R / (points - terms) (a shifted skew moves every later point of a
                              // root together: the outputs' scatter is correlated)
  Eigen::VectorXd noiseVar() const { return noiseCov.diagonal(); }
  int points = 0;
  Eigen::VectorXd value(const Eigen::VectorXd& u) const;     // outputs at u
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& u) const;  // d output / d u (outputs x n)
};

// least squares (column-pivoting QR) of every output over the points u[k] (n each) with values y[k] (one
// per output). Needs more points than terms; throws std::invalid_argument otherwise.
ResponseSurface fitResponseSurface(const std::vector<Eigen::VectorXd>& u, const std::vector<Eigen::VectorXd>& y,
                                   const Eigen::VectorXd& centre, double scale);

// the covariance of measured values against the surface: the measurement's own (traceCov) + the runs' scatter
Eigen::MatrixXd totalCovariance(const ResponseSurface& s, const Eigen::MatrixXd& traceCov);
// chi-square of outputs y against measured values: d' C^-1 d with d = y - measured, C = totalCovariance
double chiSquareOf(const Eigen::VectorXd& y, const Eigen::VectorXd& measured, const Eigen::MatrixXd& C);
// chi-square of the surface at u against measured values (chiSquareOf its value)
double surfaceChiSquare(const ResponseSurface& s, const Eigen::VectorXd& u, const Eigen::VectorXd& measured,
                        const Eigen::MatrixXd& traceCov);

// the parameters' uncertainty at u from the linearised surface: F = J' C^-1 J (C = totalCovariance),
// covariance F^-1 scaled by max(1, chi2 / dof) (a fit worse than its uncertainties widens them), in
// the units of u. Directions along which chi-square rises by less than 1 from the box's centre to its
// edge (u in [0, 1]^n: half a width each way) are flat: the outputs do not determine them.
struct FitUncertainty {
  Eigen::MatrixXd fisher, covariance;   // covariance empty when F is singular
  std::vector<double> sigma;            // per parameter (NaN when it has a part along a flat direction)
  double scale = 1;
  double chi2 = 0;
  int dof = 0;
  std::vector<Eigen::VectorXd> flat;    // unit vectors in u
};
FitUncertainty uncertaintyAt(const ResponseSurface& s, const Eigen::VectorXd& u, const Eigen::VectorXd& measured,
                             const Eigen::MatrixXd& traceCov);

}  // namespace rootsim
