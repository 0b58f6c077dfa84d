#pragma once
// The damage evolution function F(D) of Eq. (13) and everything derived from it.
// Internally the damage is carried as the integrity x = 1 - D (docs/model.md pitfall 3):
// near D = 1 a stored D would keep only ~1e-7 relative precision in 1 - D.
namespace ecm {

struct DamageLawParams {
  double youngsModulus = 0.0;     // E (MPa), the band's elastic modulus
  double tensileStrength = 0.0;   // f_t' (MPa)
  double softeningModulus = 0.0;  // E_p (MPa)
  double softeningExponent = 0.0; // n (-), 0 < n < 0.5 for a finite fracture energy
  void validate() const;          // throws ParameterError
};

// F as a function of the integrity x = 1 - D, Eq. (13):
// F = f_t'^2/(2E) [(E + E_p x^n) / (E x + E_p x^n)]^2. F(1) = f_t'^2/(2E); F ~ x^(-2n) as x -> 0.
double damageFunction(const DamageLawParams& p, double integrity);
// The same with x^n given (spares the pow).
double damageFunction(const DamageLawParams& p, double integrity, double integrityPower);
// dF/dx (negative: F grows as damage grows).
double damageFunctionSlope(const DamageLawParams& p, double integrity);

// The integrity x in (0, x0] with F(x) = y, for y >= F(x0): Newton in s = x^n, where the
// equation E - r E x - (r - 1) E_p x^n = 0 (r = sqrt(2 E y)/f_t') is concave and decreasing,
// so Newton started at x0 approaches the root monotonically from the right and never leaves
// the bracket. Returns x0 when y <= F(x0) (damage is irreversible).
double integrityForDrivingForce(const DamageLawParams& p, double y, double x0 = 1.0);
// The same solve without the irreversibility check: requires y > F(x0).
double solveIntegrity(const DamageLawParams& p, double y, double x0);
// The same with x0^n given and x^n returned as well (each spares a pow in the hot path).
struct PoweredIntegrity {
  double x;   // integrity
  double xn;  // x^n
};
PoweredIntegrity solveIntegrity(const DamageLawParams& p, double y, const PoweredIntegrity& start);
// dF/dx with x^n given.
double damageFunctionSlope(const DamageLawParams& p, double integrity, double integrityPower);

// Energy dissipated per unit volume of band while the integrity drops from xOld to xNew
// (xNew <= xOld): int_{D_old}^{D_new} F dD (during loading Y = F). Gauss-Legendre in
// t = x^(1 - 2n), where the x^(-2n) singularity of F becomes a bounded, smooth integrand.
double dissipationBetween(const DamageLawParams& p, double xOld, double xNew);
// The same when F(xOld) and F(xNew) are known (a loading update has both: the threshold and Y):
// Simpson's rule with one more F for an increment of x below 0.1 % (rel. error < 1e-13 there),
// dissipationBetween otherwise.
double dissipationBetween(const DamageLawParams& p, double xOld, double xNew, double fOld, double fNew);

// Work per unit volume of band to complete failure, int_0^1 F(D) dD (docs/model.md, identities);
// times the band width h this is the fracture energy G_F. Adaptive GSL quadrature (QAG, Gauss-Kronrod 31) of the regularised integrand, rel. 1e-11.
double dissipationToFailure(const DamageLawParams& p);

// Uniaxial stress of the law at integrity x on the monotonic branch (Y = F(x)):
// sigma = x sqrt(2 E F(x)) (closed form used by tests, calibration and the point driver).
double uniaxialStress(const DamageLawParams& p, double integrity);

}  // namespace ecm
