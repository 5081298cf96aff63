// AndersonMixerOf (deform/anderson.h), the Anderson acceleration of AnARAP's
// positions and of coupled rotations: each proposal is the textbook type-II
// mix (Walker & Ni 2011) of the pairs given so far, g_k - dG theta with
// theta = argmin |f_k - dF theta| over the last `window` differences (with
// the mixer's relative Tikhonov term), for every window up to the most it
// keeps, as the ring of differences fills, wraps and is reset, for states of
// an odd and an even number of values (the pass's pairs and its tail).
#include <cmath>
#include <deque>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "deform/anderson.h"

using namespace aniso;

namespace {

// A state of `rows` rows, its values drawn from `random`: the differences
// are then far from parallel and the least-squares problem well posed, so
// that the proposals can be compared to rounding (a nearly singular one
// would compare the regularization's rounding instead).
template <typename State>
State state(int rows, std::mt19937& random) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  State s(rows, State::ColsAtCompileTime);
  for (Eigen::Index i = 0; i < s.size(); ++i) s.data()[i] = value(random);
  return s;
}

// The proposal from the explicit history of f = g - x and g (newest last).
template <typename State>
State reference_proposal(const std::deque<State>& f, const std::deque<State>& g, int window) {
  const int m = std::min(window, static_cast<int>(f.size()) - 1);
  const Eigen::Index n = f.back().size();
  Eigen::MatrixXd dF(n, m), dG(n, m);
  for (int a = 0; a < m; ++a) {
    const std::size_t newer = f.size() - 1 - a;
    for (Eigen::Index i = 0; i < n; ++i) {
      dF(i, a) = f[newer].data()[i] - f[newer - 1].data()[i];
      dG(i, a) = g[newer].data()[i] - g[newer - 1].data()[i];
    }
  }
  Eigen::MatrixXd A = dF.transpose() * dF;
  A.diagonal().array() += 1e-10 * A.diagonal().maxCoeff();
  const Eigen::Map<const Eigen::VectorXd> f_k(f.back().data(), n);
  const Eigen::VectorXd theta = A.ldlt().solve(dF.transpose() * f_k);
  State out = g.back();
  Eigen::Map<Eigen::VectorXd>(out.data(), n) -= dG * theta;
  return out;
}

template <typename State>
void check_against_reference(int rows) {
  for (int window = 1; window <= 8; ++window) {
    CAPTURE(rows, window);
    AndersonMixerOf<State> mixer(window);
    std::mt19937 random(static_cast<unsigned>(17 * window + rows));
    std::deque<State> f, g;
    State proposal;
    for (int k = 0; k < 14; ++k) {
      CAPTURE(k);
      if (k == 9) {
        // After a rejected proposal the mixer forgets its differences; the
        // last pair stays a true one.
        mixer.reset();
        f.erase(f.begin(), f.end() - 1);
        g.erase(g.begin(), g.end() - 1);
      }
      const State x = state<State>(rows, random), gk = state<State>(rows, random);
      f.push_back(gk - x);
      g.push_back(gk);
      const bool mixed = mixer.propose(x, gk, proposal);
      REQUIRE(mixed == (k > 0));
      if (!mixed) {
        CHECK(proposal == gk);
        continue;
      }
      const State expected = reference_proposal(f, g, window);
      CHECK((proposal - expected).cwiseAbs().maxCoeff() <= 1e-10 * (1.0 + gk.cwiseAbs().maxCoeff()));
    }
  }
}

}  // namespace

TEST_CASE("Anderson mixer: positions, an odd number of values, every window", "[anderson]") {
  check_against_reference<Positions>(7);  // 21 values: the pass's pairs and its tail
}

TEST_CASE("Anderson mixer: quaternions, an even number of values, every window", "[anderson]") {
  check_against_reference<RotationMixer::StateType>(6);  // 24 values
}
