// Manipulability (Yoshikawa) and the joint-limit penalty (Tsai; Vahrenkamp et al.) of chain configurations.
#include "octoreach/manipulability.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "kinematics/chain_checks.hpp"

namespace octoreach {
namespace {

using Gram = Eigen::Matrix<double, 6, 6>;

// J J^T (6 x 6) of the geometric Jacobian at q.
Gram gram(const Chain& chain, const double* q) {
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, chain.dof());
  chain.fk_jacobian(q, J.data());
  return J * J.transpose();
}

// Eigenvalues of G, ascending.
Eigen::Matrix<double, 6, 1> eigenvalues(const Gram& G) {
  return Eigen::SelfAdjointEigenSolver<Gram>(G, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace

int jacobian_rank(const Chain& chain) {
  if (chain.dof() == 0) return 0;
  // 32 configurations: a rank the chain has somewhere it has almost everywhere (singular sets have measure zero).
  std::mt19937_64 rng(0x5EED);
  int rank = 0;
  for (int i = 0; i < 32 && rank < 6; ++i) {
    const Eigen::VectorXd q = chain.random_configuration(rng);
    const auto ev = eigenvalues(gram(chain, q.data()));
    const double top = std::max(ev[5], 1e-300);
    int r = 0;
    for (int k = 0; k < 6; ++k) r += ev[k] > 1e-12 * top;  // singular values above 1e-6 of the largest
    rank = std::max(rank, r);
  }
  return rank;
}

double manipulability(const Chain& chain, const Eigen::VectorXd& q, int rank) {
  detail::check_joint_vector(chain, q);
  if (!q.allFinite()) throw std::invalid_argument("manipulability needs a finite configuration");
  if (rank < 1 || rank > 6) throw std::invalid_argument("rank must be in [1, 6], got " + std::to_string(rank));
  if (chain.dof() == 0) return 0.0;
  const Gram G = gram(chain, q.data());
  if (rank == 6) {  // sqrt(det G) is the product of the Cholesky factor's diagonal (G positive definite)
    const Eigen::LLT<Gram> llt(G);
    if (llt.info() == Eigen::Success) return llt.matrixLLT().diagonal().prod();
  }
  const auto ev = eigenvalues(G);
  double product = 1.0;
  for (int k = 6 - rank; k < 6; ++k) product *= std::max(0.0, ev[k]);
  return std::sqrt(product);
}

double joint_limit_penalty(const Chain& chain, const Eigen::VectorXd& q) {
  detail::check_joint_vector(chain, q);
  if (!q.allFinite()) throw std::invalid_argument("joint_limit_penalty needs a finite configuration");
  double product = 1.0, k = 1.0;
  for (int i = 0; i < chain.dof(); ++i) {
    if (chain.continuous()[i]) continue;
    const double lo = chain.lower()[i], hi = chain.upper()[i], span = hi - lo;
    if (!(span > 0)) continue;  // a joint without range neither moves nor is penalised
    // At a limit or past it (a configuration outside the range) the factor is 0: the penalty is total.
    product *= std::max(0.0, (q[i] - lo) * (hi - q[i])) / (span * span);
    k *= 4.0;
  }
  return k == 1.0 ? 1.0 : 1.0 - std::exp(-k * product);
}

}  // namespace octoreach
