// Unit tests of the particle–wheel contact law against analytic values and LIGGGHTS' formulas.
#include "contact_law.h"

#include <gtest/gtest.h>

#include <cmath>

namespace wc = wheelsim::contact;

namespace {

wc::PairConstants hertzConstants(double e = 0.5, double mu = 0.5) {
  wc::Material particle{5.0e7, 0.3}, wheel{2.0e11, 0.3};
  wc::PairMaterial pair;
  pair.coefficientRestitution = e;
  pair.coefficientFriction = mu;
  return wc::makePairConstants(particle, wheel, pair, wc::ContactSettings{});
}

TEST(Hertz, StaticForceIsFourThirdsYeffSqrtRDeltaToTheThreeHalves) {
  const auto pc = hertzConstants();
  wc::ContactState s;
  s.radius = 2.0e-3;
  s.mass = 1.0e-4;
  for (double delta : {1e-7, 1e-6, 1e-5, 1e-4}) {
    s.overlap = delta;
    wc::ContactHistory h{};
    const auto r = wc::evaluate(pc, s, 1e-6, true, h);
    const double expected = 4.0 / 3.0 * pc.Yeff * std::sqrt(s.radius) * std::pow(delta, 1.5);
    EXPECT_NEAR(r.force.z(), expected, 1e-12 * expected) << "delta = " << delta;
    EXPECT_NEAR(r.force.x(), 0.0, 1e-12 * expected);
  }
}

} // namespace
