// The progress bar of iterations that stop at a cap or at a tolerance on the
// relative energy change (base/convergence_progress.h), on made-up energy
// sequences whose changes are known, and on a real flattening; and the
// factorization's, by the work done.
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "anisoform/deformer.h"
#include "anisoform/session.h"
#include "anisoform/session_flatten.h"
#include "base/convergence_progress.h"
#include "geometry/supernodal_ldlt.h"
#include "test_support.h"

using namespace aniso;

TEST_CASE("convergence progress: without a tolerance it is the share of the cap", "[progress]") {
  ConvergenceProgress progress(8, 0.0);
  for (int k = 1; k <= 8; ++k) CHECK(progress.update(k, 1.0 + std::pow(0.5, k)) == Approx(k / 8.0));
}

TEST_CASE("convergence progress: a change falling geometrically to the tolerance fills the bar evenly", "[progress]") {
  // E_k = 1 + 0.1^k: relative changes fall tenfold per iteration, from 9e-2
  // to the tolerance 1e-8 in 7 more iterations, on a cap of 500.
  ConvergenceProgress progress(500, 1e-8);
  std::vector<double> fractions;
  for (int k = 1; k <= 10; ++k) fractions.push_back(progress.update(k, 1.0 + std::pow(0.1, k)));
  CHECK(fractions[0] == Approx(1.0 / 500));  // no change measured yet
  for (std::size_t k = 1; k < fractions.size(); ++k) CHECK(fractions[k] >= fractions[k - 1]);
  // Halfway down the log scale (4 of the 8 decades to 1e-8) is about halfway.
  CHECK(fractions[5] == Approx(0.5).margin(0.1));
  CHECK(fractions[8] > 0.9);
  CHECK(fractions.back() < 1.0);  // 1 only when the caller says the iterations ended
}

TEST_CASE("convergence progress: it never goes back, and a new stage starts its own scale", "[progress]") {
  ConvergenceProgress progress(100, 1e-8);
  progress.update(1, 2.0);
  progress.update(2, 1.0);    // first change 0.5
  const double reached = progress.update(3, 1.0 - 1e-5);
  CHECK(reached > 0.5);
  CHECK(progress.update(4, 0.5) == reached);  // a large change again: the bar stays
  // A stage whose energy is measured differently (the flattening's refinement).
  CHECK(progress.update(4, std::numeric_limits<double>::quiet_NaN()) == reached);
  CHECK(progress.update(5, 40.0) == reached);  // 40 against 0.5 is no change of this stage
  CHECK(progress.update(6, 20.0) == reached);  // its first change, 0.5
  CHECK(progress.update(7, 20.0 * (1.0 - 1e-7)) > reached);
}

TEST_CASE("convergence progress: a change measured over a window follows the mean, not each step", "[progress]") {
  // Steps that alternate between a large and a tiny gain: each tiny one alone
  // reads as converged, the mean of the last 4 does not.
  ConvergenceProgress single(0, 1e-6), windowed(0, 1e-6, 4);
  double energy = 1.0, single_fraction = single.update(0, energy), windowed_fraction = windowed.update(0, energy);
  for (int k = 1; k <= 9; ++k) {
    energy *= k % 2 ? 0.99 : 1.0 - 1e-8;
    single_fraction = single.update(k, energy);
    windowed_fraction = windowed.update(k, energy);
  }
  CHECK(single_fraction > 0.9);
  CHECK(windowed_fraction < 0.3);
}

TEST_CASE("staged progress: each stage fills its share after the ones before it; the cap is the floor", "[progress]") {
  StagedProgress progress({{0.2, 1e-4}, {0.8, 1e-4}}, 1000);
  // Stage 0: changes 1e-1, 1e-2, ..., 1e-5 (below its end).
  double energy = 1.0;
  std::vector<double> fractions;
  for (int k = 1; k <= 6; ++k) {
    fractions.push_back(progress.update(0, k, energy));
    energy *= 1.0 - std::pow(0.1, k);
  }
  CHECK(fractions.front() == Approx(0.001));  // the cap's share, 1 of 1,000
  CHECK(fractions.back() == Approx(0.2 * 0.99));
  // Stage 1, an energy of its own: it starts where stage 0's share ends,
  // and fills from its own first change.
  CHECK(progress.update(1, 7, 50.0) == Approx(0.2));
  CHECK(progress.update(1, 8, 25.0) == Approx(0.2));  // its first change, 0.5
  const double half = progress.update(1, 9, 25.0 * (1.0 - std::sqrt(0.5 * 1e-4)));  // halfway down its log scale
  CHECK(half == Approx(0.2 + 0.8 * 0.5).margin(1e-9));
  CHECK(progress.update(0, 10, 1.0) == half);  // never back
  CHECK(progress.update(1, 1000, 25.0) == 1.0);  // the cap
}

TEST_CASE("convergence progress: a flattening's bar fills with its iterations and most of it before it ends",
          "[progress][flatten]") {
  // The hemisphere converges at about 70 of the 1,000 iterations allowed:
  // counted against the cap the bar stood at 7 % when the pattern came (at
  // 16 % with the 500 cap of the time). Through the refinement's stages the
  // bar followed only the last one's energy: the hand's stood at 8 % after
  // half of its 154 iterations, and jumped from 44 % to the end.
  for (const char* name : {"open/hemisphere.obj", "open/hand_lowres.obj"}) {
    INFO(name);
    Session session;
    session.adopt_mesh(test::load(name), {});
    std::vector<double> fractions;
    session.set_progress([&fractions](ProgressStage stage, double fraction) {
      if (stage == ProgressStage::Flatten) fractions.push_back(fraction);
    });
    SessionFlatten request;
    request.su = 0.8;
    request.direction_given = false;  // the longest axis, as the app's default
    const SessionFlattenResult result = session.flatten(request);
    REQUIRE(result.metrics.converged);
    REQUIRE(fractions.size() >= 20);  // one per iteration, and the end
    double largest_step = 0.0;
    for (std::size_t k = 1; k < fractions.size(); ++k) {
      CHECK(fractions[k] >= fractions[k - 1]);
      if (k + 1 < fractions.size()) largest_step = std::max(largest_step, fractions[k] - fractions[k - 1]);
    }
    CHECK(fractions.back() == 1.0);
    const double before_the_end = fractions[fractions.size() - 2];
    const double halfway = fractions[fractions.size() / 2];
    INFO(result.metrics.iterations << " iterations; at half of them " << halfway << ", before the end "
                                   << before_the_end << ", largest step " << largest_step);
    CHECK(before_the_end > 0.8);  // measured 0.95 and 0.99
    CHECK(halfway > 0.3);         // measured 0.61 and 0.49
    CHECK(halfway < 0.8);
    CHECK(largest_step < 0.2);    // measured 0.14 and 0.11
  }
}

TEST_CASE("set-up progress: the copy, the workspace, the factorization's analysis and twentieths, the iterations' "
          "structures, on prepare_step's scale; the same factor",
          "[progress]") {
  // The app showed "Preparing the solver 0 %" for the whole factorization
  // (15 s on a 470k-vertex mesh in the browser): only 0 and 1 were reported.
  const Mesh armadillo = test::load("closed/armadillo.off");
  std::vector<double> fractions;
  const auto deform_reporting = [&](bool report) {
    Deformer deformer(armadillo);
    if (report) {
      deformer.set_progress([&fractions](ProgressStage stage, double fraction) {
        if (stage == ProgressStage::Factorize) fractions.push_back(fraction);
      });
    }
    DeformRequest request;  // AnARAP on the whole mesh, along x
    request.transform.su = 1.2;
    request.max_iterations = 2;
    return deformer.deform(request).V;
  };
  const Positions quiet = deform_reporting(false);
  const Positions heard = deform_reporting(true);
  CHECK(heard == quiet);  // reporting changes nothing computed
  // The same scale as the background preparation's (Deformer::prepare_step):
  // an edit that comes in the middle of it carries its share on. Each part
  // reports where it ends; the factorization also where it starts.
  const double factor_span = kSetupFactorizedShare - kSetupWorkspaceShare;
  REQUIRE(fractions.size() >= 15);
  CHECK(fractions[0] == kSetupLaplacianShare);
  CHECK(fractions[1] == kSetupWorkspaceShare);
  CHECK(fractions[2] == kSetupWorkspaceShare);  // the factorization starts: its ordering comes next
  CHECK(fractions[3] == Approx(kSetupWorkspaceShare + factor_span * kAnalysedShare));
  CHECK(fractions[fractions.size() - 2] == Approx(kSetupFactorizedShare));
  CHECK(fractions.back() == 1.0);
  for (std::size_t k = 1; k < fractions.size(); ++k) CHECK(fractions[k] >= fractions[k - 1]);
  for (std::size_t k = 3; k + 1 < fractions.size(); ++k) CHECK(fractions[k] > fractions[k - 1]);
}
