#pragma once
// Internal: sine and cosine of one angle together, inlined, for the chain's kinematics (a descent step of IK
// turns every joint once, and the capability map's build takes millions of steps). fdlibm's method: the angle
// reduced by the nearest multiple n of pi/2 with pi/2 split in three parts (two of 33 bits, whose products with n
// are exact, and the rest), then fdlibm's minimax polynomials of sin and cos on [-pi/4, pi/4]. Within 2 ulp of
// std::sin / std::cos where |angle| < 1e5 (joint angles); larger or non-finite angles take std::sin / std::cos.
#include <cmath>

namespace octoreach::detail {

inline void sin_cos(double x, double& s, double& c) {
  if (!(std::abs(x) < 1e5)) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kPio2a = 1.57079632673412561417e+00;  // first 33 bits of pi/2
  constexpr double kPio2b = 6.07710050630396597660e-11;  // the next 33
  constexpr double kPio2c = 2.02226624879595063154e-21;  // pi/2 - kPio2a - kPio2b
  constexpr double kRound = 6755399441055744.0;  // 1.5 * 2^52: adding it rounds to the nearest integer
  const double n = (x * kTwoOverPi + kRound) - kRound;
  const double r = ((x - n * kPio2a) - n * kPio2b) - n * kPio2c;
  const double z = r * r;
  const double sr = r + r * z * (-1.66666666666666324348e-01 +
                                 z * (8.33333333332248946124e-03 +
                                      z * (-1.98412698298579493134e-04 +
                                           z * (2.75573137070700676789e-06 +
                                                z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
  const double cr = 1.0 - 0.5 * z +
                    z * z * (4.16666666666666019037e-02 +
                             z * (-1.38888888888741095749e-03 +
                                  z * (2.48015872894767294178e-05 +
                                       z * (-2.75573143513906633035e-07 +
                                            z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  switch (static_cast<long long>(n) & 3) {
    case 0: s = sr; c = cr; break;
    case 1: s = cr; c = -sr; break;
    case 2: s = -sr; c = -cr; break;
    default: s = -cr; c = sr; break;
  }
}

}  // namespace octoreach::detail
