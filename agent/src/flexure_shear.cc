// Saint-Venant's flexure shear on a rectangle (agent/flexure_shear.h).
#include <agent/flexure_shear.h>

#include <algorithm>
#include <cmath>

namespace agent {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSeriesTolerance = 1e-16;
constexpr int kMaxTerms = 100000;

/// cosh(x) / cosh(b) and sinh(x) / cosh(b) for |x| <= b, without overflow (exp forms).
double cosh_ratio(double x, double b) {
  const double ax = std::abs(x);
  return std::exp(ax - b) * (1 + std::exp(-2 * ax)) / (1 + std::exp(-2 * b));
}
double sinh_ratio(double x, double b) {
  const double ax = std::abs(x);
  return std::copysign(std::exp(ax - b) * -std::expm1(-2 * ax) / (1 + std::exp(-2 * b)), x);
}

/// k = nu / (1 + nu) V / I of an h by d rectangle.
double flexure_k(double h, double d, double shear, double poisson) {
  return poisson / (1 + poisson) * shear / (d * h * h * h / 12);
}

}  // namespace

FlexureShear flexure_shear(double y, double z, double h, double d, double shear, double poisson) {
  const double k = flexure_k(h, d, shear, poisson), I = d * h * h * h / 12;
  // Each term's bound: 1 / n^2 times cosh(2 n pi y / d) / cosh(n pi h / d) <= exp(-2 n pi (h/2 - |y|) / d).
  const double decay = 2 * kPi * std::max(0.0, 0.5 * h - std::abs(y)) / d;
  double cos_sum = 0, sin_sum = 0;
  const double first = std::exp(-decay);
  for (int n = 1; n <= kMaxTerms; ++n) {
    const double alpha = 2 * n * kPi / d, beta = n * kPi * h / d, sign = n % 2 ? -1.0 : 1.0;
    const double c = sign / (double(n) * n);
    cos_sum += c * std::cos(alpha * z) * cosh_ratio(alpha * y, beta);
    sin_sum += c * std::sin(alpha * z) * sinh_ratio(alpha * y, beta);
    if (std::exp(-n * decay) / (double(n) * n) < kSeriesTolerance * first) break;
  }
  const double series = d * d / (2 * kPi * kPi);
  const double tau0 = shear / (2 * I) * (0.25 * h * h - y * y);
  return {tau0 + k * ((3 * z * z - 0.25 * d * d) / 6 - series * cos_sum), k * series * sin_sum};
}

std::vector<FlexureShear> flexure_correction_means(const std::vector<double>& y_planes, const std::vector<double>& z_planes,
                                                   double h, double d, double shear, double poisson) {
  const std::size_t ny = y_planes.size() - 1, nz = z_planes.size() - 1;
  const double k = flexure_k(h, d, shear, poisson), series = d * d / (2 * kPi * kPi);
  std::vector<FlexureShear> out(ny * nz);
  // The polynomial's mean over [z0, z1]: (z1^3 - z0^3) / (6 (z1 - z0)) - d^2 / 24, the same at every y.
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t m = 0; m < nz; ++m) {
      const double z0 = z_planes[m], z1 = z_planes[m + 1];
      out[j * nz + m].at = k * ((z1 * z1 * z1 - z0 * z0 * z0) / (6 * (z1 - z0)) - d * d / 24);
    }
  double dy = h, dz = d;  // the smallest boxes: the terms' bound
  for (std::size_t j = 0; j < ny; ++j) dy = std::min(dy, y_planes[j + 1] - y_planes[j]);
  for (std::size_t m = 0; m < nz; ++m) dz = std::min(dz, z_planes[m + 1] - z_planes[m]);
  // Separable: per n, the y means of cosh / cosh and sinh / cosh per row, the z means of cos and sin per box.
  std::vector<double> y_cosh(ny), y_sinh(ny), z_cos(nz), z_sin(nz);
  double first = 0;
  for (int n = 1; n <= kMaxTerms; ++n) {
    const double alpha = 2 * n * kPi / d, beta = n * kPi * h / d, sign = n % 2 ? -1.0 : 1.0;
    const double c = sign / (double(n) * n);
    for (std::size_t j = 0; j < ny; ++j) {
      const double y0 = alpha * y_planes[j], y1 = alpha * y_planes[j + 1];
      y_cosh[j] = (sinh_ratio(y1, beta) - sinh_ratio(y0, beta)) / (y1 - y0);
      y_sinh[j] = (cosh_ratio(y1, beta) - cosh_ratio(y0, beta)) / (y1 - y0);
    }
    for (std::size_t m = 0; m < nz; ++m) {
      const double z0 = alpha * z_planes[m], z1 = alpha * z_planes[m + 1];
      z_cos[m] = (std::sin(z1) - std::sin(z0)) / (z1 - z0);
      z_sin[m] = (std::cos(z0) - std::cos(z1)) / (z1 - z0);
    }
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t m = 0; m < nz; ++m) {
        out[j * nz + m].at -= k * series * c * z_cos[m] * y_cosh[j];
        out[j * nz + m].aw += k * series * c * z_sin[m] * y_sinh[j];
      }
    const double bound = std::min(1.0, 2 / (alpha * dy)) * std::min(1.0, 2 / (alpha * dz)) / (double(n) * n);
    if (n == 1) first = bound;
    if (bound < kSeriesTolerance * first) break;
  }
  return out;
}

}  // namespace agent
