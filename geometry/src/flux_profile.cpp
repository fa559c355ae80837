// A tool's flux profile (definitions: flux_profile.hpp, docs/deposition.md).
#include "coverbench/flux_profile.hpp"

#include <cmath>

#include "coverbench/input_error.hpp"

namespace coverbench {

FluxDensity::FluxDensity(const FluxProfile& profile, double r)
    : kind_(profile.kind), r_(r), sigma_(profile.sigma), exponent_(profile.beta - 1.0) {
  if (!(r > 0.0)) kind_ = FluxProfile::Kind::None;
  switch (kind_) {
    case FluxProfile::Kind::Uniform: denominator_ = 2.0 * r; break;
    case FluxProfile::Kind::Gaussian:
      two_sigma_squared_ = 2.0 * sigma_ * sigma_;
      denominator_ = sigma_ * std::sqrt(2.0 * M_PI) * std::erf(r / (sigma_ * std::sqrt(2.0)));
      break;
    case FluxProfile::Kind::Beta: {
      // B(1/2, beta) = Gamma(1/2) Gamma(beta) / Gamma(beta + 1/2)
      const double b = std::exp(std::lgamma(0.5) + std::lgamma(profile.beta) - std::lgamma(profile.beta + 0.5));
      denominator_ = r * b;
      break;
    }
    case FluxProfile::Kind::None: break;
  }
}

double FluxDensity::operator()(double x) const {
  if (!(std::fabs(x) <= r_)) return 0.0;
  switch (kind_) {
    case FluxProfile::Kind::None: return 0.0;
    case FluxProfile::Kind::Uniform: return 1.0 / denominator_;
    case FluxProfile::Kind::Gaussian: return std::exp(-x * x / two_sigma_squared_) / denominator_;
    case FluxProfile::Kind::Beta: {
      const double u = x / r_;
      return std::pow(std::fmax(0.0, 1.0 - u * u), exponent_) / denominator_;
    }
  }
  return 0.0;
}

double FluxProfile::density(double x, double r) const { return FluxDensity(*this, r)(x); }

double FluxProfile::spread(double r) const {
  switch (kind) {
    case Kind::Gaussian: return sigma;
    case Kind::Beta: return r / std::sqrt(2.0 * beta + 1.0);
    default: return r / std::sqrt(3.0);
  }
}

std::string toString(FluxProfile::Kind kind) {
  switch (kind) {
    case FluxProfile::Kind::None: return "none";
    case FluxProfile::Kind::Uniform: return "uniform";
    case FluxProfile::Kind::Gaussian: return "gaussian";
    case FluxProfile::Kind::Beta: return "beta";
  }
  return "none";
}

std::string toString(FluxProfile::Flow flow) { return flow == FluxProfile::Flow::Speed ? "speed" : "constant"; }

bool parseFlow(const std::string& name, FluxProfile::Flow& flow) {
  for (FluxProfile::Flow f : {FluxProfile::Flow::Constant, FluxProfile::Flow::Speed})
    if (toString(f) == name) {
      flow = f;
      return true;
    }
  return false;
}

bool parseFluxProfileKind(const std::string& name, FluxProfile::Kind& kind) {
  for (FluxProfile::Kind k : {FluxProfile::Kind::None, FluxProfile::Kind::Uniform, FluxProfile::Kind::Gaussian, FluxProfile::Kind::Beta})
    if (toString(k) == name) {
      kind = k;
      return true;
    }
  return false;
}

std::string FluxProfile::describe(double s) const {
  std::string out = toString(kind) + " profile";
  if (kind == Kind::Gaussian) out = "gaussian profile, sigma " + shortNumber(sigma) + " m";
  if (kind == Kind::Beta) out = "beta profile, beta " + shortNumber(beta);
  out += ", " + shortNumber(rate) + " m3/s, fan depth " + shortNumber(depthFor(s)) + " m";
  if (target > 0.0) out += ", target " + shortNumber(target) + " \u00b5m";
  return flow == Flow::Speed ? out + ", flow follows speed" : out;
}

std::string FluxProfile::label() const {
  if (!set()) return "";
  std::string out = toString(kind);
  if (kind == Kind::Gaussian) out += " " + shortNumber(sigma) + " m";
  if (kind == Kind::Beta) out += " " + shortNumber(beta);
  if (rate != FluxProfile{}.rate) out += ", " + shortNumber(rate) + " m3/s";
  if (depth != 0.0) out += ", fan depth " + shortNumber(depth) + " m";
  if (target != 0.0) out += ", target " + shortNumber(target) + " um";
  if (flow == Flow::Speed) out += ", flow follows speed";
  return out;
}

void FluxProfile::check(double s, const std::string& source) const {
  if (kind == Kind::Gaussian && !(sigma >= s / 50.0 && sigma <= 100.0))
    throw InputError(source, "sigma", "must be in [s/50, 100] m (s/50 = " + shortNumber(s / 50.0) + " m), got " + shortNumber(sigma));
  if (kind == Kind::Beta && !(beta >= 1.0 && beta <= 100.0))
    throw InputError(source, "beta", "must be in [1, 100], got " + shortNumber(beta));
  if (!(rate > 0.0 && rate <= 1.0)) throw InputError(source, "rate", "must be in (0, 1] m3/s, got " + shortNumber(rate));
  // At least s/1000: a fan far thinner than the raster's cell (1e-50 m) lost its coat to rounding.
  if (!(depth == 0.0 || (depth >= s / 1000.0 && depth <= s)))
    throw InputError(source, "depth",
                     "must be in [s/1000, s] m (or 0: s/10; s = " + shortNumber(s) + " m), got " + shortNumber(depth));
  if (!(target == 0.0 || (target > 0.0 && target <= kMaxTarget)))
    throw InputError(source, "target", "must be in (0, 1e+06] um (or 0: none), got " + shortNumber(target));
}


FluxProfile fluxProfileOf(const ProfileOptions& options, double s, const ProfileSpelling& spelling) {
  const ProfileSpelling& n = spelling;
  auto source = [&](const std::string& name) { return n.source.empty() ? name : n.source; };
  const std::string kind_field = n.source.empty() ? "profile" : "kind";
  FluxProfile profile;
  if (!parseFluxProfileKind(options.profile, profile.kind))
    throw InputError(source(n.kind), kind_field,
                     "must be none, uniform, gaussian or beta, got '" + shownBytes(options.profile) + "'");
  const bool gaussian = profile.kind == FluxProfile::Kind::Gaussian, beta = profile.kind == FluxProfile::Kind::Beta;
  // As a config reads tool.profile: each value belongs to its profile, and none goes unused.
  if (!profile.set() && (options.sigma || options.beta || options.rate || options.fan_depth || options.target || options.flow))
    throw InputError(source(n.kind), kind_field,
                     n.sigma + ", " + n.beta + ", " + n.rate + ", " + n.depth + ", " + n.target + " and " + n.flow + " need " +
                         n.kind);
  if (options.sigma && !gaussian) throw InputError(source(n.sigma), "sigma", "belongs to " + n.kind + " gaussian");
  if (options.beta && !beta) throw InputError(source(n.beta), "beta", "belongs to " + n.kind + " beta");
  if (gaussian && !options.sigma) throw InputError(source(n.sigma), "sigma", "is missing: a gaussian profile's standard deviation, m");
  if (beta && !options.beta) throw InputError(source(n.beta), "beta", "is missing: a beta profile's exponent");
  if (options.sigma) profile.sigma = *options.sigma;
  if (options.beta) profile.beta = *options.beta;
  if (options.rate) profile.rate = *options.rate;
  if (options.fan_depth) profile.depth = *options.fan_depth;
  if (options.target) {
    // Given, a target is a coat aimed at: 0 (none) is only the default.
    if (!(*options.target > 0.0 && *options.target <= FluxProfile::kMaxTarget))
      throw InputError(source(n.target), "target", "must be in (0, 1e+06] um, got " + shortNumber(*options.target));
    profile.target = *options.target;
  }
  if (options.flow && !parseFlow(*options.flow, profile.flow))
    throw InputError(source(n.flow), "flow", "must be constant or speed, got '" + shownBytes(*options.flow) + "'");
  if (profile.set()) profile.check(s, n.checked);
  return profile;
}

double passRipple(const FluxProfile& profile, double s, double d) {
  const double r = s / 2.0;
  if (!profile.set() || !(d > 0.0) || !(r > 0.0)) return NAN;
  constexpr int kSamples = 512;
  double worst = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double x = (i + 0.5) * d / kSamples;
    double g = 0.0;
    // The passes at k d within r of x.
    for (long k = static_cast<long>(std::floor((x - r) / d)); k <= static_cast<long>(std::ceil((x + r) / d)); ++k)
      g += profile.density(x - static_cast<double>(k) * d, r);
    worst = std::fmax(worst, std::fabs(g * d - 1.0));
  }
  return worst;
}

double evenSpacing(const FluxProfile& profile, double s, double tolerance, double* ripple) {
  if (ripple) *ripple = NAN;
  if (!profile.set() || !(s > 0.0) || !(tolerance >= 0.0)) return 0.0;
  const double step = s / 1000.0;
  for (int k = 0; k <= 900; ++k) {
    const double d = s - k * step;
    const double here = passRipple(profile, s, d);
    if (!(here <= tolerance)) continue;
    double lo = d, hi = d + step;  // lo within the tolerance, hi (the step before) not
    if (k > 0)
      for (int it = 0; it < 30; ++it) {
        const double mid = 0.5 * (lo + hi);
        (passRipple(profile, s, mid) <= tolerance ? lo : hi) = mid;
      }
    if (ripple) *ripple = passRipple(profile, s, lo);
    return lo;
  }
  return 0.0;
}

}  // namespace coverbench
