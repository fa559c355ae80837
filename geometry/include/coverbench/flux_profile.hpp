#pragma once
/// A tool's flux profile: how a spraying tool (paint, plaster) spreads what it sprays across its
/// width. A value type of the tool (ToolParams::profile): planners read it to space their rows for
/// an even coat, the metrics engine to compute the coat's thickness (deposition.hpp). Definitions
/// and formulae: docs/deposition.md.
///
/// Across the fan the flux follows f(x), x the signed distance from the tool's centre across the
/// motion, f = 0 for |x| > r (r = s / 2) and the integral of f over [-r, r] equal to 1:
///   uniform:  f(x) = 1 / (2r)
///   gaussian: f(x) = exp(-x^2 / (2 sigma^2)) / (sigma sqrt(2 pi) erf(r / (sigma sqrt 2)))
///   beta:     f(x) = (1 - u^2)^(beta - 1) / (r B(1/2, beta)),  u = x / r
#include <optional>
#include <string>

namespace coverbench {

/// A tool's flux profile across its width, its rate and its fan's depth (kind None: no profile).
struct FluxProfile {
  enum class Kind { None, Uniform, Gaussian, Beta };
  /// How the gun's flow follows the tool's speed: Constant sprays `rate` whatever the speed (the
  /// coat builds up where the tool slows down); Speed sprays rate x v / V, V the time model's
  /// speed (MotionLimits::speed; speed-proportional flow control, as painting robots' guns have):
  /// the same coat per metre of path at any speed, braking and stopping included.
  enum class Flow { Constant, Speed };
  Kind kind = Kind::None;
  double sigma = 0.0;   ///< gaussian: standard deviation, m
  double beta = 0.0;    ///< beta: exponent beta (f proportional to (1 - u^2)^(beta - 1))
  double rate = 1e-6;   ///< Q, m^3/s sprayed (1 ml/s)
  double depth = 0.0;   ///< l, the fan's depth along the motion, m; 0: a tenth of the tool width
  /// The coat aimed at, micrometres; 0: none, and the coat's shares are of its mean. With a target,
  /// even_share, thin_share and thick_share are of it (docs/deposition.md).
  double target = 0.0;
  Flow flow = Flow::Constant;
  bool set() const { return kind != Kind::None; }
  /// The largest target thickness accepted, micrometres (a metre of coat).
  static constexpr double kMaxTarget = 1e6;
  /// The fan's depth for a tool of width s: `depth`, or s / 10.
  double depthFor(double s) const { return depth > 0.0 ? depth : s / 10.0; }
  /// f(x), 1/m, for a tool of radius r (0 outside [-r, r]).
  double density(double x, double r) const;
  /// The profile's standard deviation across the motion (m): sigma for a Gaussian (before its
  /// truncation), r / sqrt(2 beta + 1) for beta, r / sqrt 3 for uniform.
  double spread(double r) const;
  /// The profile as run listings show it beside the tool: "uniform", "gaussian 0.02 m" (sigma),
  /// "beta 2.5", then the rate and the fan's depth where they are not the defaults and the target
  /// where there is one, and a flow that follows the speed ("beta 2.5, 2e-06 m3/s, fan depth 0.05 m,
  /// target 25 um, flow follows speed"); "" for none.
  std::string label() const;
  /// "gaussian profile, sigma 0.02 m, 1e-06 m3/s, fan depth 0.01 m" for a tool of width s, then
  /// ", target 25 µm" where there is a target and ", flow follows speed" where it does.
  std::string describe(double s) const;
  /// Throws InputError(source, field, problem) for a value out of range for a tool of width s:
  /// sigma in [s/50, 100 m], beta in [1, 100], rate in (0, 1] m^3/s, depth in (0, s] (0: the default),
  /// target in (0, 1e6] um or 0 (none).
  void check(double s, const std::string& source) const;
};
/// A profile's f(x) for a tool of radius r with its constants (the normalisation, a gamma function
/// and an error function) computed once: FluxProfile::density, bit for bit, at a fraction of its
/// cost where one profile is evaluated many times (the coat's raster).
class FluxDensity {
 public:
  FluxDensity(const FluxProfile& profile, double r);
  double operator()(double x) const;

 private:
  FluxProfile::Kind kind_;
  double r_, sigma_, exponent_, two_sigma_squared_ = 0.0, denominator_ = 0.0;
};

/// "uniform", "gaussian", "beta" (or "none").
std::string toString(FluxProfile::Kind kind);
/// "constant", "speed".
std::string toString(FluxProfile::Flow flow);
/// The flow named `name` ("constant" or "speed"); false when there is none.
bool parseFlow(const std::string& name, FluxProfile::Flow& flow);
/// The kind named `name`; false when there is none.
bool parseFluxProfileKind(const std::string& name, FluxProfile::Kind& kind);

/// A profile as the command line and Python give it: the kind's name ("none", "uniform",
/// "gaussian", "beta") and each value, unset where not given (rate 1e-6 m^3/s, depth s / 10).
struct ProfileOptions {
  std::string profile = "none";
  /// The kind was given (the command line's --profile): `none` then means no profile, not "the
  /// plan file's".
  bool named = false;
  std::optional<double> sigma, beta, rate, fan_depth, target;
  std::optional<std::string> flow;  ///< "constant" or "speed"
};
/// How a caller names the kind and the values in its messages. The default is the command line's:
/// each error's source is the flag it is about ("--sigma: sigma: belongs to --profile gaussian"),
/// range errors are the "command line"'s. With `source` set, every error has that source and
/// names the value by its key (Python: "profile: sigma: belongs to kind gaussian").
struct ProfileSpelling {
  std::string kind = "--profile", sigma = "--sigma", beta = "--beta", rate = "--rate", depth = "--fan-depth",
              target = "--target", flow = "--flow";
  std::string source;                   ///< empty: the flag each error is about
  std::string checked = "command line";  ///< the source of out-of-range values (FluxProfile::check)
};
/// The profile the options describe for a tool of width s, read as a config reads tool.profile:
/// each value belongs to its kind, none goes unused, a kind's own value is required, and every
/// value is in range (FluxProfile::check). InputError, spelled by `spelling`, otherwise.
FluxProfile fluxProfileOf(const ProfileOptions& options, double s, const ProfileSpelling& spelling = {});

/// The ripple of parallel passes d apart: the sum of the profile repeated every d,
/// g(x) = sum_k f(x - k d), has mean 1/d over a period; the ripple is max |g(x) d - 1| over x,
/// sampled at 512 points of a period (a tool of width s, r = s / 2).
double passRipple(const FluxProfile& profile, double s, double d);
/// The widest spacing of parallel passes, in [s/10, s], whose ripple (passRipple) is at most
/// `tolerance`: the steady coat between the rows' ends is then within that fraction of its mean. A
/// uniform profile gives s (flat with no overlap); a Gaussian or beta fan a spacing under s (its
/// passes must overlap). Scanned from s down in steps of s/1000, the first spacing within the
/// tolerance refined by bisection against the step before it; 0 when no spacing down to s/10 is
/// within it. `ripple` (if given) receives the ripple at the spacing returned.
double evenSpacing(const FluxProfile& profile, double s, double tolerance, double* ripple = nullptr);

}  // namespace coverbench
